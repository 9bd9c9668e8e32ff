// fts-client's game loop: drives the protocol's client endpoint over one UDP socket,
// reads keys from the raw terminal, and draws at its own frame rate (its own ball
// predicted, the others a jitter buffer's delay behind the server). With main_client.cpp
// the only translation units of the client with Asio in them (through fts_io's socket).
#include "game.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "fts/io/client_socket.hpp"
#include "fts/protocol/connection.hpp"
#include "net/board_request.hpp"
#include "net/clock.hpp"
#include "net/interpolate.hpp"
#include "net/link_meters.hpp"
#include "net/link_stats.hpp"
#include "net/net_timing.hpp"
#include "net/session_store.hpp"
#include "term/io.hpp"
#include "term/keys.hpp"
#include "term/terminal.hpp"
#include "ui/chat_line.hpp"
#include "ui/game_frame.hpp"
#include "ui/hud.hpp"
#include "ui/panel.hpp"
#include "ui/pointer_steer.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"
#include "ui/welcome_view.hpp"

namespace asio = fts::io::asio;
using fts::io::udp;
namespace proto = fts::protocol;
using namespace fts::client;

namespace {

// The game loop: keys in, commands and input out through the connection, snapshots in,
// a frame drawn. The socket is fts_io's, the reconnect rule and the input pacing the
// protocol's (ClientConnection), and the loss meter and event feed are net/ pieces.
class Game {
 public:
  Game(asio::io_context& io, Options o, udp::endpoint server)
      : io_(io), opts_(std::move(o)), socket_(io, server), timer_(io),
        store_(state_dir(std::getenv("XDG_STATE_HOME"), std::getenv("HOME")), opts_.host + ":" + opts_.port),
        conn_(connection_config(opts_, opts_.fresh ? std::nullopt : store_.load()), /*resume_when_lost=*/true) {
    view_.color = color_wanted(std::getenv("NO_COLOR"), std::getenv("TERM"));
    view_.guest = !opts_.identity.has_value();
    view_.fine = fine_field(opts_);
    net_ = NetTiming(opts_.predict);
    conn_.connect(now_ms());
    last_rx_ms_ = now_ms();
    connect_ms_ = now_ms();
    follow_socket();
    flush();
    frame();
  }

  int exit_code() const { return exit_code_; }
  // The link and prediction figures of the session (--stats-file).
  std::string stats_json(std::uint64_t now) const {
    const auto& st = conn_.endpoint().stats();
    return net_.stats_json(now - started_ms_, st.rtt_ms, net_.loss_percent(), st.bytes_sent, st.bytes_received);
  }
  const std::string& exit_message() const { return exit_message_; }

 private:
  // A new connection from a fresh socket, with the saved token unless --new or expired.
  void connect_again(std::uint64_t now, std::string why) {
    conn_ = proto::ClientConnection(connection_config(opts_, opts_.fresh ? std::nullopt : store_.load()),
                                    /*resume_when_lost=*/true);
    conn_.connect(now);
    connect_ms_ = last_rx_ms_ = now;
    noted_attempt_ = 0;
    socket_.restart();
    follow_socket();
    note(std::move(why));
  }

  // How long the server keeps this player's lives and coins for its return: while a
  // match runs, until it ends; else the reconnect window (PROTOCOL.md 5.4, issue 37).
  std::string kept_for() const {
    if (phase() == proto::Phase::play || phase() == proto::Phase::shop)
      return "Your lives and coins are kept until this match ends";
    return "Your coins are kept " + std::to_string(reconnect_window_s(conn_.endpoint().welcome())) + " s";
  }

  // The saved token was refused (expired, or the server restarted): a new player.
  void start_fresh(std::uint64_t now) {
    store_.forget();
    opts_.fresh = true;
    connect_again(now, "The old session has expired: playing as a new player.");
  }

  // Back after an idle kick: the saved token takes the player (and its coins) back into
  // its room while the server keeps it (the reconnect window); after that, a new player.
  void rejoin(std::uint64_t now) {
    idle_ = false;
    connect_again(now, "Coming back...");
  }

  // Each connection attempt from a fresh socket, to where the room is (fts_io).
  void follow_socket() {
    const auto f = socket_.follow(conn_.attempt(), conn_.moves(), conn_.moved_to(),
                                  [this](const udp::endpoint&, std::span<const std::uint8_t> bytes) {
                                    if (done_) return;
                                    last_rx_ms_ = now_ms();
                                    conn_.endpoint().receive(bytes, last_rx_ms_);
                                  });
    if (f.moved) notice("Room moved to another server: playing on.");
    if (!f.error.empty() && !f.opened) throw std::runtime_error(f.error);
    if (!f.error.empty()) note("Not followed: " + sanitize(f.error, 80) + ".");
  }

  void flush() {
    for (auto& d : conn_.endpoint().take_datagrams()) socket_.send(d);
  }

  void finish(int code, std::string message) {
    if (conn_.state() == proto::ClientState::connected) {
      conn_.leave(now_ms());
      flush();
    }
    done_ = true;
    exit_code_ = code;
    exit_message_ = std::move(message);
    timer_.cancel();
    socket_.close();
    io_.stop();
  }

  void frame() {
    const std::uint64_t now = now_ms();
    if (const int sig = term::stop_signal()) return finish(0, "stopped by signal " + std::to_string(sig));
    read_keys(now);
    if (idle_over(opts_, now - std::max(keys_.last_key_ms(), started_ms_))) return finish(kIdleExitCode, idle_text(opts_));
    if (done_) return;
    conn_.update(now);
    follow_socket();
    absorb(now);
    if (done_) return;
    // Predicting: the tick the own ball is drawn at this frame, and its frames name.
    if (net_.predicting()) net_.own_tick(now, std::max(0.0, conn_.endpoint().stats().rtt_ms));
    send_input(now);
    flush();
    draw(now);
    if (!opts_.stats_file.empty() && now >= stats_written_ms_ + kStatsEveryMs) {
      stats_written_ms_ = now;
      write_stats_file(opts_.stats_file, stats_json(now));
    }
    timer_.expires_after(std::chrono::milliseconds(1000 / opts_.fps));
    timer_.async_wait([this](boost::system::error_code ec) {
      if (!ec && !done_) frame();
    });
  }

  proto::Phase phase() const {
    const proto::Snapshot* s = buffer_.newest();
    return s != nullptr ? s->phase : proto::Phase::lobby;
  }

  void read_keys(std::uint64_t now) {
    for (const KeyEvent& e : keys_.read(now)) handle_key(e, now);
  }

  void chat_key(const KeyEvent& e, std::uint64_t now) {
    const auto line = edit_chat_line(view_, e, kChatMaxChars);
    if (line && !line->empty() && conn_.state() == proto::ClientState::connected)
      pending_chats_.insert(conn_.endpoint().send_chat(*line, now));
  }

  void handle_key(const KeyEvent& e, std::uint64_t now) {
    if (e.key == Key::focus_out) steer_.stop();  // a window without the focus steers nothing
    if (idle_ && e.action != KeyAction::release && !is_report(e)) {  // kicked as idle: q leaves, any key plays
      if (e.key == Key::ctrl_c || (e.key == Key::character && e.ch == 'q')) return finish(0, "");
      return rejoin(now);
    }
    if (view_.chat_open) return chat_key(e, now);
    const Action a = action_of(e, phase());
    const bool connected = conn_.state() == proto::ClientState::connected;
    // Quitting asks first: q (or Ctrl-C) once asks, q or y again quits, any other key stays.
    const bool yes = e.key == Key::character && e.ch == 'y';
    if (quit_asked_ && (a.kind == ActionKind::quit || yes)) return finish(0, "");
    if (quit_asked_ && e.action != KeyAction::release && !is_report(e)) {  // a moved pointer is no answer
      quit_asked_ = false;
      view_.status.clear();
      note("Staying.");
      return;
    }
    switch (a.kind) {
      case ActionKind::quit:
        quit_asked_ = true;
        note("Quit? Press q again (or y) to leave, any other key to stay. " + kept_for() + ".");
        return;
      case ActionKind::move:
        if (auto d = direction_of(e)) hold_.on_key(*d, e, now);
        steer_.stop();  // the keys take over until the pointer moves again
        break;
      case ActionKind::pointer:
        if (!opts_.mouse) break;
        if (e.action == KeyAction::press) aim_at(e.col, e.row);
        if (!e.motion && e.action == KeyAction::press && e.button == 0 && phase() == proto::Phase::play) fire_ = true;
        break;
      case ActionKind::chat:
        view_.chat_open = true;
        view_.chat_draft.clear();
        hold_.release_all();
        break;
      case ActionKind::follow:
        if (const proto::Snapshot* s = buffer_.newest())
          view_.follow_id = next_follow(*s, followed(*s, view_), view_.my_player_id);
        break;
      case ActionKind::fire: fire_ = true; break;
      case ActionKind::buy:
        // 's' and 'a' also steer: a key still held (or repeating) from the level that just
        // ended must not spend coins. Purchases count from a moment after the shop opens.
        if (now - shop_opened_ms_ < kShopGraceMs) break;
        if (connected) {
          const std::uint32_t rid = conn_.endpoint().send_command(proto::CommandOp::buy, a.item, now);
          pending_buys_[rid] = a.item;
          view_.shop_result = std::string("Buying ") + a.item + "...";
          view_.shop_result_ms = now;
        }
        break;
      case ActionKind::ready:
        if (connected)
          conn_.endpoint().send_command(phase() == proto::Phase::over ? proto::CommandOp::play_again : proto::CommandOp::ready,
                                 0, now);
        break;
      case ActionKind::none: break;
    }
  }

  void send_input(std::uint64_t now) {
    if (conn_.state() != proto::ClientState::connected) return;
    proto::InputFrame f;
    if (phase() != proto::Phase::play) steer_.stop();
    const bool steering = phase() == proto::Phase::play && steer_.active();
    if (!steering) steered_at_ms_ = 0;
    if (steering) {
      const Steer st = mouse_steer(now);
      f.move_x = static_cast<std::int8_t>(st.x);
      f.move_y = static_cast<std::int8_t>(st.y);
    } else if (phase() == proto::Phase::play) {
      f.move_x = static_cast<std::int8_t>(hold_.move_x(now));
      f.move_y = static_cast<std::int8_t>(hold_.move_y(now));
    } else {
      hold_.release_all();
    }
    view_.mouse_steering = steer_.active();
    f.fire = fire_;
    // Predicting, a frame names the tick it acts at: the one the own ball is drawn at
    // (PROTOCOL.md 4.5); never one before a frame already sent.
    if (net_.predicting()) f.tick = net_.stamp(net_.shown_tick());
    view_.thrust_x = f.move_x;
    view_.thrust_y = f.move_y;
    net_.thrust(f.move_x, f.move_y, now);
    // The lean uplink (PROTOCOL.md 4.5), as the bots: a frame on change (at most every
    // 20 ms; a fire is kept until then) and a keep-alive every 50 ms. What the server will
    // apply is what was sent: the prediction takes the frames that went out.
    if (conn_.endpoint().hold_input(f, now) != 0) net_.sent(f);
    fire_ = false;
  }

  // The pointer's cell as a point of the platform: steering starts (or ends, off it).
  void aim_at(int col, int row) {
    const proto::Snapshot* s = buffer_.newest();
    if (s == nullptr || s->phase != proto::Phase::play) return;
    const Viewport v = arena_viewport(last_size_, view_, *s);
    const bool on = col >= v.col0 && col < v.col0 + v.cols && row >= v.row0 && row < v.row0 + v.rows;
    steer_.aim(v.x_of(col), v.y_of(row), on);
  }

  // The thrust toward the aim (ui/pointer_steer.hpp) for our ball where it is when this
  // frame acts: predicting, the own ball at the tick the frame names (the inputs in flight
  // included); else the newest snapshot's, carried on by its velocity over the snapshot's
  // age plus half a round trip (which misses the thrust of the frames in flight: on a
  // loaded machine the ball braked late and coasted off the edge).
  Steer mouse_steer(std::uint64_t now) {
    const proto::Snapshot* s = buffer_.newest();
    if (s == nullptr) return {};
    std::optional<SteerBall> ball = steer_ball(*s, view_.my_player_id);
    // The thrust decided now holds until the next frame: on a loaded machine frames come
    // late, so the gap since the last one (at most 0.25 s) is part of the delay too.
    const double gap_s = steered_at_ms_ != 0 ? std::min(0.25, static_cast<double>(now - steered_at_ms_) / 1000.0) : 0.0;
    steered_at_ms_ = now;
    double delay_s = gap_s;
    const std::optional<proto::BallState> own = ball && net_.predicting() ? net_.own_ball(now) : std::nullopt;
    if (own && own->id == ball->id) {
      ball->x = own->x, ball->y = own->y, ball->vx = own->vx, ball->vy = own->vy;
    } else {
      const double ticks_old = std::max(0.0, net_.server_tick(now) - static_cast<double>(s->tick));
      const double rtt_s = conn_.endpoint().stats().rtt_ms > 0 ? conn_.endpoint().stats().rtt_ms / 1000.0 : 0.0;
      delay_s += ticks_old / tick_rate_hz(conn_.endpoint().welcome()) + rtt_s / 2;
    }
    return steer_.update(ball ? &*ball : nullptr, view_.arena_width_u, view_.arena_height_u, delay_s);
  }

  void absorb(std::uint64_t now) {
    using S = proto::ClientState;
    proto::ClientEndpoint& endpoint = conn_.endpoint();
    if (conn_.state() == S::connected && endpoint.welcome() && noted_attempt_ != conn_.attempt()) {
      noted_attempt_ = conn_.attempt();
      const proto::Welcome& w = *endpoint.welcome();
      show_welcome(view_, w);
      net_.on_welcome(w);
      events_.start_at(w.server_tick);  // not what happened here before we came back
      note(w.reconnected ? "Reconnected: welcome back." : "Connected.");
      back_until_ms_ = w.reconnected ? now + 3000 : 0;  // and in the HUD, where no event scrolls it away
      if (!w.room.empty()) {
        note(std::string(w.spectator ? "Watching room " : "Room ") + sanitize(w.room, 8) +
             (w.spectator ? "." : ": friends join with --join " + sanitize(w.room, 8)));
        rooms_rid_ = endpoint.send_command(proto::CommandOp::rooms, 0, now);
      }
      board_.forget();  // a new session: its rids start again
      ask_board(now);
      std::string why;
      if (!store_.save(w.token, why)) note("Cannot keep the session for a restart: " + sanitize(why, 100));
    }
    for (auto& s : endpoint.take_snapshots()) {
      if (s.phase == proto::Phase::shop && phase() != proto::Phase::shop) shop_opened_ms_ = now;
      // The match's end is recorded before a board asked after it is read (PROTOCOL.md
      // 4.7c): the waiting screen and the next level-end show the new best.
      if ((s.phase == proto::Phase::over || s.phase == proto::Phase::lobby) && s.phase != phase()) ask_board(now);
      for (const auto& p : s.players)
        if (view_.names.size() < kMaxNames || view_.names.count(p.id) > 0) view_.names[p.id] = p.name;
      net_.on_snapshot(s, view_.my_player_id, now);  // and the loss meter
      read_events(s);
      buffer_.push(std::move(s));
    }
    for (auto& b : endpoint.take_boards()) {
      if (!board_.answered_by(b)) continue;
      view_.board = std::move(b);
      view_.board_note.clear();
    }
    board_.retry_if_lost(endpoint, now);
    for (const auto& r : endpoint.take_results()) {
      if (board_.take_result(r, now)) {
        // A server without profiles has no board: the waiting screen stays as it was.
        if (!r.ok)
          view_.board_note = r.code == proto::to_string(proto::ResultCode::no_profiles)
                                 ? std::string()
                                 : "Leaderboard: " + refusal_text(r.code, r.message, 0, nullptr) + ".";
        continue;
      }
      if (r.command_rid == rooms_rid_ && rooms_rid_ != 0) {
        note("Public rooms: " + (r.message.empty() ? std::string("none") : sanitize(r.message, 200)));
        rooms_rid_ = 0;
        continue;
      }
      const proto::Snapshot* newest = buffer_.newest();
      const PlayerState* me = newest != nullptr ? find_player(*newest, view_.my_player_id) : nullptr;
      if (pending_chats_.erase(r.command_rid) > 0) {
        if (!r.ok) note("Chat not sent: " + refusal_text(r.code, r.message, 0, me) + ".");
        continue;
      }
      auto it = pending_buys_.find(r.command_rid);
      if (it == pending_buys_.end()) continue;
      const std::string msg = sanitize(r.message, 120);
      view_.shop_result = r.ok ? (msg.empty() ? std::string("Bought ") + it->second + "." : msg)
                               : "Cannot buy: " + refusal_text(r.code, r.message, it->second, me) + ".";
      view_.shop_result_ms = now;
      pending_buys_.erase(it);
    }
    for (const auto& c : endpoint.take_chats()) push_log(chat_log_line(c, now, kChatMaxChars));
    // Connection trouble: show it after 2 s of silence; the connection resumes with the
    // token by itself (ClientConnection) until the reconnect window has passed.
    const S st = conn_.state();
    if (st == S::refused && endpoint.error() && proto::has_code(*endpoint.error(), proto::ErrorCode::bad_token) && !opts_.fresh)
      return start_fresh(now);
    if (idle_) return;
    if (st == S::refused && endpoint.error() && proto::has_code(*endpoint.error(), proto::ErrorCode::idle)) {
      // The server treats an idle player as one who quit: its seat is free, its progress
      // kept until the match ends (PROTOCOL.md 5.4). Stay, and come back on a key (issue 26).
      idle_ = true;
      steer_.stop();
      view_.chat_open = false;
      note("Idle for a while: you left the match. " + kept_for() + ".");
      view_.status = "idle: press a key to play again, q to quit";
      return;
    }
    if (st == S::refused) {
      const auto& err = endpoint.error();
      return finish(1, "server: " + (err ? sanitize(err->message, 200) : std::string("refused")));
    }
    // How long until the client gives up, so that a wrong address is not a blank wait.
    const std::uint64_t limit = proto::ClientConfig{}.connect_timeout_ms, spent = now - connect_ms_;
    const std::string connecting = "connecting to " + opts_.host + ":" + opts_.port + "... " +
                                   std::to_string(spent < limit ? (limit - spent + 999) / 1000 : 0) + " s";
    if (conn_.token().empty()) {
      if (st == S::timed_out) return finish(1, "no answer from the server at " + opts_.host + ":" + opts_.port);
      view_.status = connecting;
      return;
    }
    if (conn_.gone()) return finish(1, "connection lost: the server is gone");
    const bool silent = now - last_rx_ms_ > 2000;
    // Not welcomed yet on this connection (a saved token being tried): connecting, not lost.
    if (noted_attempt_ == 0 && st != S::connected) view_.status = connecting;
    else view_.status = (silent || st != S::connected) ? "connection lost, reconnecting..."
                        : now < back_until_ms_                 ? "Reconnected: welcome back"
                                                               : "";
    view_.ping_ms = endpoint.stats().rtt_ms > 0 ? endpoint.stats().rtt_ms : -1;
    view_.loss_percent = net_.loss_percent();
  }

  // Asks for the leaderboard, unless a request is on its way (net/board_request.hpp).
  void ask_board(std::uint64_t now) { board_.ask(conn_.endpoint(), now); }

  void note(std::string line) { push_log(LogLine{std::move(line), now_ms()}); }
  // A line of the log that also holds the footer for a moment (ViewState::notice).
  void notice(std::string line) { view_.notice = line; view_.notice_ms = now_ms(); note(std::move(line)); }

  void push_log(LogLine line) {
    view_.messages.push_back(std::move(line));
    if (view_.messages.size() > kLogKeep) view_.messages.erase(view_.messages.begin());
  }

  void read_events(const proto::Snapshot& s) {
    for (const auto& e : events_.fresh(s)) {
      tally_event(view_.scores, e);
      const std::string line = describe_event(e, s, view_.my_player_id, &view_.names);
      if (!line.empty()) note(line);
      if (e.kind == proto::EventKind::purchase && e.a == view_.my_player_id) {
        view_.shop_result = line;
        view_.shop_result_ms = now_ms();
      }
      if (e.kind == proto::EventKind::level_started) view_.shop_result.clear();
    }
  }

  void draw(std::uint64_t now) {
    last_size_ = painter_.size();
    view_.now_ms = now;
    painter_.paint(game_frame(buffer_, net_, view_, last_size_, now, opts_.interp_delay_ms), view_.color);
  }

  asio::io_context& io_;
  Options opts_;
  fts::io::ClientSocket socket_;
  asio::steady_timer timer_;
  SessionStore store_;
  proto::ClientConnection conn_;
  bool quit_asked_ = false;
  std::uint64_t noted_attempt_ = 0;   // the attempt whose welcome was shown
  term::KeyReader keys_;
  term::Painter painter_;
  HoldTracker hold_;
  SnapshotBuffer buffer_;
  EventFeed events_;
  ViewState view_;
  std::map<std::uint32_t, char> pending_buys_;
  std::set<std::uint32_t> pending_chats_;  // rids of chat lines awaiting their result
  PointerSteering steer_;  // mouse steering: toward the pointer, arriving there
  std::uint64_t steered_at_ms_ = 0;  // the last frame mouse steering decided (0: not steering)
  NetTiming net_;  // server clock, remote delay, own-ball prediction and their meters (issue 28)
  std::uint64_t started_ms_ = now_ms();
  std::uint64_t stats_written_ms_ = now_ms();  // --stats-file: written every second
  static constexpr std::uint64_t kStatsEveryMs = 1000;
  TerminalSize last_size_{80, 24};
  static constexpr std::size_t kChatMaxChars = 120, kMaxNames = 256;
  std::uint32_t rooms_rid_ = 0;  // the room list asked for at the welcome
  BoardRequest board_;             // the leaderboard asked for and not come yet
  std::uint64_t last_rx_ms_ = 0, back_until_ms_ = 0;  // back_until_ms_: "welcome back" shown until
  std::uint64_t connect_ms_ = 0;  // when the current connection attempt began
  bool idle_ = false;             // kicked as idle: waiting for a key to come back
  std::uint64_t shop_opened_ms_ = 0;
  static constexpr std::uint64_t kShopGraceMs = 700;
  bool fire_ = false, done_ = false;
  int exit_code_ = 0;
  std::string exit_message_;
};

}  // namespace

namespace fts::client {

GameEnd play(asio::io_context& io, const Options& opts, const udp::endpoint& server) {
  GameEnd end;
  try {
    Game game(io, opts, server);
    io.run();
    end.code = game.exit_code();
    end.message = game.exit_message();
    if (!opts.stats_file.empty()) end.stats_json = game.stats_json(now_ms());
  } catch (const std::exception& e) {
    end.code = 1;
    end.message = std::string("error: ") + e.what();
  }
  return end;
}

}  // namespace fts::client
