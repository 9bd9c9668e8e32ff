// fts-client: the terminal game. Drives the protocol's client endpoint over one UDP
// socket, reads keys from the raw terminal, and draws at its own frame rate a fixed delay
// behind the newest snapshot. The only translation unit of the client with Asio in it.
#include <utility>
#define BOOST_ASIO_DISABLE_CO_AWAIT 1
#include <boost/asio.hpp>

#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "fts/protocol/client.hpp"
#include "term/keys.hpp"
#include "term/terminal.hpp"
#include "ui/hud.hpp"
#include "ui/interpolate.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"

namespace asio = boost::asio;
using asio::ip::udp;
namespace proto = fts::protocol;
using namespace fts::client;

namespace {

constexpr const char* kUsage =
    "Usage: fts-client --connect HOST:PORT --name NAME [options]\n"
    "\n"
    "Plays Fear The Sphere in this terminal against an fts-server.\n"
    "\n"
    "Options:\n"
    "  --connect HOST:PORT     the server (e.g. 127.0.0.1:7777)\n"
    "  --name NAME             your name: 1 to 16 printable ASCII characters\n"
    "  --encoding json|msgpack wire encoding (default msgpack)\n"
    "  --interp-delay-ms N     draw this far behind the newest snapshot (default 100)\n"
    "  --fps N                 frames drawn per second (default 60)\n"
    "  --no-kitty              do not ask the terminal for key release events\n"
    "  --help                  this text\n"
    "\n"
    "Controls: arrows or WASD thrust, space fires rockets, m s a r l x b buy in the shop,\n"
    "Enter is ready (and play again), q quits. NO_COLOR=1 turns colours off.\n";

struct Options {
  std::string host, port, name;
  proto::Encoding encoding = proto::Encoding::msgpack;
  int interp_delay_ms = 100;
  int fps = 60;
  bool kitty = true;
};

int usage_error(const std::string& msg) {
  std::cerr << "fts-client: " << msg << "\n(see fts-client --help)\n";
  return 2;
}

// Returns -1 on success, else the exit code.
int parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc) return false;
      out = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--no-kitty") {
      o.kitty = false;
    } else if (a == "--connect" && value(v)) {
      const auto colon = v.rfind(':');
      if (colon == std::string::npos || colon == 0 || colon + 1 == v.size())
        return usage_error("--connect wants HOST:PORT, got '" + v + "'");
      o.host = v.substr(0, colon);
      o.port = v.substr(colon + 1);
      if (o.host.size() > 2 && o.host.front() == '[' && o.host.back() == ']') o.host = o.host.substr(1, o.host.size() - 2);
    } else if (a == "--name" && value(v)) {
      o.name = v;
    } else if (a == "--encoding" && value(v)) {
      if (v == "json") o.encoding = proto::Encoding::json;
      else if (v == "msgpack") o.encoding = proto::Encoding::msgpack;
      else return usage_error("--encoding is json or msgpack, got '" + v + "'");
    } else if ((a == "--interp-delay-ms" || a == "--fps") && value(v)) {
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      const bool fps = a == "--fps";
      if (end == v.c_str() || *end != '\0' || n < (fps ? 1 : 0) || n > (fps ? 240 : 2000))
        return usage_error(a + (fps ? " is 1..240" : " is 0..2000") + ", got '" + v + "'");
      (fps ? o.fps : o.interp_delay_ms) = static_cast<int>(n);
    } else {
      return usage_error("unknown or incomplete option '" + a + "'");
    }
  }
  if (o.host.empty()) return usage_error("--connect HOST:PORT is required");
  if (o.name.empty() || o.name.size() > proto::kMaxNameBytes || sanitize(o.name) != o.name)
    return usage_error("--name must be 1 to 16 printable ASCII characters");
  return -1;
}

std::uint64_t now_ms() {
  using namespace std::chrono;
  return static_cast<std::uint64_t>(duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count());
}

// Snapshots lost, from the gaps in their ticks, over the last few seconds.
struct LossMeter {
  std::uint32_t last_tick = 0;
  double expected = 0, received = 0;
  void on_snapshot(std::uint32_t tick, double ticks_per_snapshot) {
    if (last_tick != 0 && tick > last_tick && ticks_per_snapshot > 0) {
      expected += std::max(1.0, (tick - last_tick) / ticks_per_snapshot);
      received += 1;
      if (expected > 100) {  // keep it recent
        expected /= 2;
        received /= 2;
      }
    }
    last_tick = tick;
  }
  double percent() const { return expected > 0 ? std::max(0.0, 100.0 * (1.0 - received / expected)) : -1; }
};

class Game {
 public:
  Game(asio::io_context& io, Options o, udp::endpoint server)
      : io_(io), opts_(std::move(o)), socket_(io), timer_(io), server_(server) {
    socket_.open(server.protocol());
    socket_.connect(server);
    view_.color = color_wanted(std::getenv("NO_COLOR"), std::getenv("TERM"));
    proto::ClientConfig cfg;
    cfg.name = opts_.name;
    cfg.encoding = opts_.encoding;
    endpoint_ = proto::ClientEndpoint(cfg);
    endpoint_.connect(now_ms());
    last_rx_ms_ = now_ms();
    flush();
    receive();
    frame();
  }

  int exit_code() const { return exit_code_; }
  const std::string& exit_message() const { return exit_message_; }

 private:
  void receive() {
    socket_.async_receive(asio::buffer(rx_), [this](boost::system::error_code ec, std::size_t n) {
      if (done_ || ec == asio::error::operation_aborted) return;  // closed: a new socket reads
      if (!ec) {
        last_rx_ms_ = now_ms();
        endpoint_.receive(std::span<const std::uint8_t>(rx_.data(), n), last_rx_ms_);
      }
      receive();  // errors such as "connection refused" (ICMP) just mean: not there yet
    });
  }

  // A fresh local port for a reconnect: to the server it is a new address carrying our
  // token, which takes the player back with a fresh session (the same address would get
  // the old session's answer again).
  void new_socket() {
    boost::system::error_code ec;
    socket_.close(ec);
    socket_ = udp::socket(io_);
    socket_.open(server_.protocol());
    socket_.connect(server_);
    receive();
  }

  void flush() {
    for (auto& d : endpoint_.take_datagrams()) {
      boost::system::error_code ec;
      socket_.send(asio::buffer(d), 0, ec);  // a lost datagram is the protocol's business
    }
  }

  void finish(int code, std::string message) {
    if (endpoint_.state() == proto::ClientState::connected) {
      endpoint_.disconnect(now_ms());
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
    if (done_) return;
    endpoint_.update(now);
    absorb(now);
    if (done_) return;
    send_input(now);
    flush();
    draw(now);
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
    char buf[256];
    std::vector<KeyEvent> events;
    for (;;) {
      const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
      if (n <= 0) break;
      auto more = keys_.feed(std::string_view(buf, static_cast<std::size_t>(n)));
      events.insert(events.end(), more.begin(), more.end());
      last_key_ms_ = now;
    }
    if (keys_.pending() && now - last_key_ms_ > 50) {
      auto more = keys_.flush();
      events.insert(events.end(), more.begin(), more.end());
    }
    for (const KeyEvent& e : events) handle_key(e, now);
  }

  void handle_key(const KeyEvent& e, std::uint64_t now) {
    const Action a = action_of(e, phase());
    const bool connected = endpoint_.state() == proto::ClientState::connected;
    switch (a.kind) {
      case ActionKind::quit: return finish(0, "");
      case ActionKind::move:
        if (auto d = direction_of(e)) hold_.on_key(*d, e, now);
        break;
      case ActionKind::fire: fire_ = true; break;
      case ActionKind::buy:
        // 's' and 'a' also steer: a key still held (or repeating) from the level that just
        // ended must not spend coins. Purchases count from a moment after the shop opens.
        if (now - shop_opened_ms_ < kShopGraceMs) break;
        if (connected) {
          const std::uint32_t rid = endpoint_.send_command(proto::CommandOp::buy, a.item, now);
          pending_buys_[rid] = a.item;
          view_.shop_result = std::string("Buying ") + a.item + "...";
        }
        break;
      case ActionKind::ready:
        if (connected)
          endpoint_.send_command(phase() == proto::Phase::over ? proto::CommandOp::play_again : proto::CommandOp::ready,
                                 0, now);
        break;
      case ActionKind::none: break;
    }
  }

  void send_input(std::uint64_t now) {
    if (endpoint_.state() != proto::ClientState::connected) return;
    proto::InputFrame f;
    if (phase() == proto::Phase::play) {
      f.move_x = static_cast<std::int8_t>(hold_.move_x(now));
      f.move_y = static_cast<std::int8_t>(hold_.move_y(now));
    } else {
      hold_.release_all();
    }
    f.fire = fire_;
    const bool changed = f.move_x != last_input_.move_x || f.move_y != last_input_.move_y || f.fire;
    if (changed || now - last_input_ms_ >= 50) {
      endpoint_.send_input(f, now);
      last_input_ = f;
      last_input_ms_ = now;
      fire_ = false;
    }
  }

  void absorb(std::uint64_t now) {
    using S = proto::ClientState;
    if (endpoint_.state() == S::connected && endpoint_.welcome()) {
      const proto::Welcome& w = *endpoint_.welcome();
      if (!welcome_seen_) {
        welcome_seen_ = true;
        token_ = w.token;
        view_.my_player_id = w.player_id;
        view_.arena_width_u = w.arena_width_u;
        view_.arena_height_u = w.arena_height_u;
        view_.shop_terms = w.shop;
        clock_.set_tick_rate(w.tick_rate_hz);
        window_ms_ = w.reconnect_window_ms;
        note(w.reconnected ? "Reconnected: welcome back." : "Connected.");
      }
      lost_since_ms_ = 0;
    }
    for (auto& s : endpoint_.take_snapshots()) {
      if (s.phase == proto::Phase::shop && phase() != proto::Phase::shop) shop_opened_ms_ = now;
      clock_.observe(s.tick, now);
      if (const auto& w = endpoint_.welcome(); w && w->snapshot_rate_hz > 0)
        loss_.on_snapshot(s.tick, static_cast<double>(w->tick_rate_hz) / w->snapshot_rate_hz);
      read_events(s);
      buffer_.push(std::move(s));
    }
    for (const auto& r : endpoint_.take_results()) {
      auto it = pending_buys_.find(r.command_rid);
      if (it == pending_buys_.end()) continue;
      const std::string msg = sanitize(r.message, 120);
      view_.shop_result = r.ok ? (msg.empty() ? std::string("Bought ") + it->second + "." : msg)
                               : "Cannot buy '" + std::string(1, it->second) + "': " + (msg.empty() ? sanitize(r.code) : msg);
      pending_buys_.erase(it);
    }
    // Connection trouble: show it after 2 s of silence, resume with the token.
    const S st = endpoint_.state();
    if (st == S::refused) {
      const auto& err = endpoint_.error();
      return finish(1, "server: " + (err ? sanitize(err->message, 200) : std::string("refused")));
    }
    if (token_.empty()) {
      if (st == S::timed_out) return finish(1, "no answer from the server at " + opts_.host + ":" + opts_.port);
      view_.status = "connecting to " + opts_.host + ":" + opts_.port + "...";
      return;
    }
    const bool silent = now - last_rx_ms_ > 2000;
    if (st == S::timed_out || st == S::disconnected) {
      if (lost_since_ms_ == 0) lost_since_ms_ = now;
      if (now - lost_since_ms_ > window_ms_) return finish(1, "connection lost: the server is gone");
      proto::ClientConfig cfg;
      cfg.name = opts_.name;
      cfg.encoding = opts_.encoding;
      cfg.token = token_;
      endpoint_ = proto::ClientEndpoint(cfg);
      endpoint_.connect(now);
      welcome_seen_ = false;
      new_socket();
    }
    view_.status = (silent || endpoint_.state() != S::connected) ? "connection lost, reconnecting..." : "";
    view_.ping_ms = endpoint_.stats().rtt_ms > 0 ? endpoint_.stats().rtt_ms : -1;
    view_.loss_percent = loss_.percent();
  }

  void note(std::string line) {
    view_.messages.push_back(std::move(line));
    if (view_.messages.size() > 8) view_.messages.erase(view_.messages.begin());
  }

  void read_events(const proto::Snapshot& s) {
    for (const auto& e : s.events) {
      const auto key = std::make_tuple(e.tick, static_cast<int>(e.kind), e.a, e.b, e.value);
      if (e.tick + 2000 < s.tick || !seen_.insert(key).second) continue;
      const std::string line = describe_event(e, s, view_.my_player_id);
      if (!line.empty()) note(line);
      if (e.kind == proto::EventKind::purchase && e.a == view_.my_player_id) view_.shop_result = line;
      if (e.kind == proto::EventKind::level_started) view_.shop_result.clear();
    }
    while (!seen_.empty() && std::get<0>(*seen_.begin()) + 2000 < s.tick) seen_.erase(seen_.begin());
  }

  void draw(std::uint64_t now) {
    TerminalSize size = term::size();
    std::string out;
    if (term::take_resized() || size.cols != size_.cols || size.rows != size_.rows) {
      out += "\x1b[0m\x1b[2J";
      last_frame_.clear();
    }
    size_ = size;
    Screen screen(size);
    if (const proto::Snapshot* newest = buffer_.newest()) {
      if (newest->phase == proto::Phase::play) {
        const double render_tick = clock_.tick_at(now) - opts_.interp_delay_ms * clock_rate() / 1000.0;
        const Frame f = buffer_.sample(render_tick);
        screen = render(*f.a, *f.b, f.alpha, size, view_);
      } else {
        screen = render(*newest, *newest, 0, size, view_);
      }
    } else {
      proto::Snapshot empty;
      screen = render(empty, empty, 0, size, view_);
    }
    const std::string frame = to_ansi(screen, view_.color);
    if (frame != last_frame_) {
      out += frame;
      last_frame_ = frame;
    }
    if (!out.empty()) term::write_all(out);
  }

  double clock_rate() const {
    const auto& w = endpoint_.welcome();
    return w && w->tick_rate_hz > 0 ? w->tick_rate_hz : 100.0;
  }

  asio::io_context& io_;
  Options opts_;
  udp::socket socket_;
  asio::steady_timer timer_;
  udp::endpoint server_;
  std::array<std::uint8_t, 2048> rx_{};
  proto::ClientEndpoint endpoint_;
  KeyDecoder keys_;
  HoldTracker hold_;
  SnapshotBuffer buffer_;
  ServerClock clock_;
  LossMeter loss_;
  ViewState view_;
  TerminalSize size_{0, 0};
  std::string last_frame_;
  std::string token_;  // the session token: a reconnect takes our player back with it
  bool welcome_seen_ = false;
  std::map<std::uint32_t, char> pending_buys_;
  std::set<std::tuple<std::uint32_t, int, std::uint32_t, std::uint32_t, std::int64_t>> seen_;
  proto::InputFrame last_input_;
  std::uint64_t last_input_ms_ = 0, last_key_ms_ = 0, last_rx_ms_ = 0, lost_since_ms_ = 0;
  std::uint64_t window_ms_ = 60000;
  std::uint64_t shop_opened_ms_ = 0;
  static constexpr std::uint64_t kShopGraceMs = 700;
  bool fire_ = false;
  bool done_ = false;
  int exit_code_ = 0;
  std::string exit_message_;
};

}  // namespace

int main(int argc, char** argv) {
  Options opts;
  if (const int code = parse(argc, argv, opts); code >= 0) return code;
  asio::io_context io;
  udp::endpoint server;
  try {
    udp::resolver resolver(io);
    server = *resolver.resolve(opts.host, opts.port).begin();
  } catch (const std::exception& e) {
    std::cerr << "fts-client: cannot resolve " << opts.host << ":" << opts.port << ": " << e.what() << "\n";
    return 1;
  }
  if (!term::enter(opts.kitty)) {
    std::cerr << "fts-client: needs a terminal (stdin and stdout must be a tty)\n";
    return 1;
  }
  int code = 0;
  std::string message;
  try {
    Game game(io, opts, server);
    io.run();
    code = game.exit_code();
    message = game.exit_message();
  } catch (const std::exception& e) {
    code = 1;
    message = std::string("error: ") + e.what();
  }
  term::leave();
  if (!message.empty()) std::cerr << "fts-client: " << message << "\n";
  return code;
}
