#include "net/udp_server.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <vector>

#include "app/console_commands.hpp"
#include "app/log.hpp"
#include "app/profile_setup.hpp"
#include "app/tick_clock.hpp"
#include "fleet/fleet.hpp"
#include "fts/room/json_fields.hpp"
#include "fts/io/udp.hpp"
#include "net/console.hpp"
#include "app/handover_frame.hpp"
#include "net/handover.hpp"

namespace fts::server {
namespace {

namespace asio = boost::asio;
using udp = asio::ip::udp;
using io::UdpSocket;
using Clock = std::chrono::steady_clock;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

class Loop {
 public:
  Loop(const Options& o, GameHost& host)
      : options_(o), host_(host), socket_(io_), tick_timer_(io_), stats_timer_(io_),
        // SIGHUP (the terminal closed, or a supervisor's stop) ends the server like
        // SIGTERM: clients are told. It does not reload the configuration.
        signals_(io_, SIGINT, SIGTERM, SIGHUP),
        clock_(static_cast<std::uint32_t>(o.tick_rate_hz * o.time_scale + 0.5), 5) {}

  int run() {
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(options_.bind, ec);
    if (ec) {
      log_record(spdlog::level::err, "bind_failed", {{"bind", options_.bind}, {"error", "not an IP address"}});
      return 1;
    }
    const udp::endpoint local(address, options_.port);
    ec = socket_.bind(local);
    if (ec) {
      log_record(spdlog::level::err, "bind_failed",
                 {{"address", options_.bind}, {"port", options_.port}, {"error", ec.message()}});
      return 1;
    }
    epoch_ns_ = now_ns();
    try {
      fleet_ = std::make_unique<Fleet>(options_);
    } catch (const std::exception& e) {
      log_record(spdlog::level::err, "bind_failed", {{"metrics", options_.metrics_address}, {"error", e.what()}});
      return 1;
    }
    const auto bound = socket_.local_endpoint();
    if (const std::string why = start_handover(bound.port()); !why.empty()) {
      log_record(spdlog::level::err, "handover_failed", {{"error", why}});
      return 1;
    }
    if (!options_.console_path.empty()) {
      console_ = std::make_unique<ConsoleServer>(io_, options_.console_path,
                                                 [this](const std::string& line) { return console_line(line); });
      // Deferred: a hand-over answers when the peer has (handover.hpp), the profile
      // commands on the profile writer's thread (the tick never waits for the database,
      // issue 41).
      console_->set_deferred([this](const std::string& line, std::function<void(std::string)> reply) {
        return deferred_console(line, std::move(reply));
      });
      if (const std::string why = console_->start(); !why.empty()) {
        log_record(spdlog::level::err, "console_failed", {{"error", why}});
        return 1;
      }
    }
    log_record(spdlog::level::info, "ready",
               {{"address", bound.address().to_string()}, {"port", bound.port()},
                {"tick_rate_hz", options_.tick_rate_hz}, {"snapshot_rate_hz", options_.snapshot_rate_hz},
                {"max_players", options_.max_players}, {"model", options_.model}, {"seed", options_.seed},
                {"time_scale", options_.time_scale}, {"record", options_.record_path}, {"max_rooms", options_.max_rooms},
                {"threads", host_.workers().threads()}, {"console", options_.console_path}, {"version", FTS_VERSION},
                {"receive_buffer", socket_.receive_buffer_bytes()}});
    fleet_->bound();
    receive();
    clock_.start(now_ns());
    schedule_tick();
    schedule_stats();
    wait_signal();
    io_.run();
    return 0;
  }

  // Stop taking players and rooms; the server stops once the last match ends or
  // --drain-grace-ms runs out (after Agones took the Shutdown). SIGTERM under Agones.
  void drain() { fleet_->drain(host_, now_ms()); }

  // One console request (a JSON line) -> its reply; datagrams it caused (a kick) go now.
  std::string console_line(const std::string& line) {
    const nlohmann::ordered_json reply = server::console_line(host_, line, now_ms());
    flush();
    // A drain with no room left ends the process at the next tick, after this reply is
    // written (stopping here would drop it).
    // Replies quote only text the server holds clean; should one not be UTF-8, it is
    // replaced rather than thrown out of the console's handler.
    return reply.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  // Rooms that move (issue 42): the channel exists with --fleet-secret, and takes rooms
  // with --handover-listen.
  std::string start_handover(std::uint16_t game_port) {
    if (options_.fleet_secret_path.empty()) return "";
    std::string why;
    std::string key = handover::read_secret_file(options_.fleet_secret_path, why);
    if (key.empty()) return why;
    handover_ = std::make_unique<HandoverChannel>(io_, host_, std::move(key), game_port, [this] { return now_ms(); },
                                                  [this] { flush(); });
    if (options_.handover_listen.empty()) return "";
    if (why = handover_->listen(options_.handover_listen); !why.empty()) return why;
    log_record(spdlog::level::info, "handover_listening", {{"address", options_.handover_listen}, {"port", handover_->port()}});
    return "";
  }

  // A console request answered later, or false (console_line answers it now).
  bool deferred_console(const std::string& line, std::function<void(std::string)> reply) {
    // Read as console_line reads it (the strict parser: a key given twice is refused, so
    // {"cmd":"top","cmd":"handover",...} cannot slip past); what does not read is
    // console_line's to refuse, naming why.
    std::string why;
    const auto parsed = room::parse_json(line, why, kConsoleMaxDepth);
    if (!parsed) return false;
    const nlohmann::json& req = *parsed;
    if (!req.is_object() || !req.contains("cmd") || !req["cmd"].is_string()) return false;
    const std::string cmd = req["cmd"].get<std::string>();
    const auto text = [](const nlohmann::ordered_json& j) {
      return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
    };
    if (cmd == "handover" && handover_) {
      const auto word = [&](const char* k) { return req.contains(k) && req[k].is_string() ? req[k].get<std::string>() : ""; };
      log_record(spdlog::level::info, "console", {{"request", req.dump()}, {"deferred", true}});
      hand_over(word("room"), word("peer"), [reply, text](nlohmann::ordered_json j) { reply(text(j)); });
      return true;
    }
    auto* writer = host_.profiles();
    if (!writer || (cmd != "top" && cmd != "profile")) return false;
    log_record(spdlog::level::info, "console", {{"request", req.dump()}, {"deferred", true}});
    writer->query([req, reply](profiles::Store* store) {
      reply(server::profiles_reply(store, req).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    });
    return true;
  }

  // `handover ROOM PEER`, or `handover all PEER`: the server drains (no new rooms) and
  // hands every room over; the reply lists each room's outcome.
  void hand_over(const std::string& room, const std::string& peer, HandoverChannel::Done done) {
    if (room != "all") return handover_->hand_over(room, peer, std::move(done));
    handed_over_all_ = true;
    host_.stop_new_rooms();
    std::vector<std::string> codes;
    for (auto id : host_.room_ids())
      if (const Room* r = host_.room(id)) codes.push_back(r->code());
    if (codes.empty()) return done({{"ok", true}, {"rooms", nlohmann::ordered_json::array()}, {"draining", true}});
    struct All {
      std::size_t left;
      nlohmann::ordered_json rooms = nlohmann::ordered_json::array();
      bool ok = true;
      HandoverChannel::Done done;
    };
    auto all = std::make_shared<All>(All{codes.size(), {}, true, std::move(done)});
    handover_->hand_over(codes, peer, [all](const std::string& code, nlohmann::ordered_json j) {
      all->ok = all->ok && j.value("ok", false);
      j["room"] = code;
      all->rooms.push_back(std::move(j));
      if (--all->left == 0) all->done({{"ok", all->ok}, {"rooms", all->rooms}, {"draining", true}});
    });
  }

  // --handover-to: a drain (the console's, or SIGTERM under Agones) first hands every room
  // to that peer. A room refused is tried again a second later, kDrainAttempts times in
  // all (a Service may send the next connection to another peer; a full one may have room
  // by then); then it stays and plays on, as a drain's rooms do, and the drain goes on as
  // before (the process ends with its last room, or its grace).
  static constexpr int kDrainAttempts = 3;
  void hand_over_on_drain() {
    if (handed_over_all_ || !handover_ || options_.handover_to.empty() || !host_.draining()) return;
    hand_over("all", options_.handover_to, [this](nlohmann::ordered_json j) {
      std::size_t moved = 0;
      for (const auto& r : j["rooms"]) {
        moved += r.value("ok", false);
        if (!r.value("ok", false)) retry_on_drain(r.value("room", std::string()), 2);
      }
      log_record(spdlog::level::info, "drain_handover",
                 {{"rooms", j["rooms"].size()}, {"moved", moved}, {"ok", j.value("ok", false)}});
    });
  }
  void retry_on_drain(std::string code, int attempt) {
    auto timer = std::make_shared<asio::steady_timer>(io_, std::chrono::seconds(1));
    timer->async_wait([this, timer, code = std::move(code), attempt](const boost::system::error_code& e) {
      if (e || stopping_ || !host_.room_by_code(code)) return;  // the room ended meanwhile
      handover_->hand_over(code, options_.handover_to, [this, code, attempt](nlohmann::ordered_json j) {
        const bool ok = j.value("ok", false);
        log_record(spdlog::level::info, "drain_handover_retry", {{"room", code}, {"attempt", attempt}, {"ok", ok}});
        if (!ok && attempt < kDrainAttempts) retry_on_drain(code, attempt + 1);
      });
    });
  }

  // The console's drain: the last room has ended, the process exits 0. Under Agones the
  // fleet's drain takes over instead (it tells Agones first; see schedule_tick).
  void stop_if_drained() {
    if (!host_.drained() || stopping_) return;
    if (console_ && console_->unanswered() != 0) return;  // a reply still to write (the next tick looks again)
    stopping_ = true;
    log_record(spdlog::level::info, "shutdown", {{"reason", "drained"}});
    host_.shutdown(now_ms());
    flush();
    io_.stop();
  }

 private:
  // Under Agones the first SIGTERM drains (Kubernetes' stop); any other signal, or a
  // second one, stops at once.
  void wait_signal() {
    signals_.async_wait([this](const boost::system::error_code& e, int sig) {
      if (e) return;
      if (sig == SIGTERM && fleet_->agones() && !fleet_->draining()) {
        drain();
        wait_signal();
        return;
      }
      stop({{"signal", sig}});
    });
  }

  void stop(std::initializer_list<LogField> why) {
    log_record(spdlog::level::info, "shutdown", why);
    host_.shutdown(now_ms());
    flush();
    io_.stop();
  }

  std::uint64_t now_ms() const { return static_cast<std::uint64_t>((now_ns() - epoch_ns_) / 1'000'000); }

  // The socket is read when the loop wakes for a tick (and at least every kReadEveryNs
  // when ticks are further apart: schedule_tick), not when a datagram comes: one wake-up
  // per tick instead of one per arrival. A datagram waits for the tick at most, which is
  // where its input is used anyway; a hello's answer waits that long too (10 ms at the
  // default 100 Hz). Measured at 256 clients: 0.72 of the CPU (BENCHMARKS.md, issue 39).
  static constexpr std::int64_t kReadEveryNs = 10'000'000;

  void receive() {
    socket_.start_receiving(
        [this](const udp::endpoint& from, std::span<const std::uint8_t> bytes) {
          host_.receive(io::to_text(from), bytes, now_ms());
        },
        {}, UdpSocket::Wake::when_asked);
  }

  // Addresses travel as text through the sans-I/O layers and are parsed back here, so
  // no table of senders can be filled (or flushed) by a flood of spoofed sources.
  void flush() {
    host_.take_datagrams(datagrams_);  // last flush's buffers go back for reuse
    outgoing_.clear();
    for (const auto& d : datagrams_)
      if (const auto to = io::endpoint_from_text(d.to)) outgoing_.push_back({*to, d.bytes});
    socket_.send_batch(outgoing_);
  }

  void schedule_tick() {
    const std::int64_t wake_ns = std::min(clock_.next_deadline_ns(), now_ns() + kReadEveryNs);
    tick_timer_.expires_at(Clock::time_point(std::chrono::nanoseconds(wake_ns)));
    tick_timer_.async_wait([this](const boost::system::error_code& ec) {
      if (ec) return;
      socket_.take_waiting();
      const std::uint64_t skipped_before = clock_.skipped();
      const std::uint32_t n = clock_.due(now_ns());
      if (n == 0) {  // a read between ticks: its answers (a hello's) go now
        flush();
        return schedule_tick();
      }
      for (std::uint32_t i = 0; i < n; ++i) {
        const auto start = Clock::now();
        host_.tick(now_ms());
        flush();
        const std::chrono::duration<double> took = Clock::now() - start;
        host_.stats().tick_us.push_back(took.count() * 1e6);
        fleet_->observe_tick(took.count());
      }
      hand_over_on_drain();
      if (fleet_->agones()) {
        if (host_.draining() && !fleet_->draining()) drain();  // the console's drain, told to Agones
      } else {
        stop_if_drained();
        if (stopping_) return;
      }
      if (clock_.skipped() != skipped_before) {
        host_.stats().skipped_ticks += clock_.skipped() - skipped_before;
        if (now_ns() - last_skip_log_ns_ > 1'000'000'000) {  // at most once a second
          log_record(spdlog::level::warn, "ticks_skipped", {{"total", clock_.skipped()}});
          last_skip_log_ns_ = now_ns();
        }
      }
      fleet_->tick(host_, clock_.ticks_run(), clock_.skipped(), now_ms());
      if (fleet_->finished(now_ms())) {
        stop({{"drained", true}});
        return;
      }
      schedule_tick();
    });
  }

  void schedule_stats() {
    stats_timer_.expires_after(std::chrono::milliseconds(options_.stats_interval_ms));
    stats_timer_.async_wait([this](const boost::system::error_code& ec) {
      if (ec) return;
      Stats& s = host_.stats();
      const auto p = percentiles(s.tick_us);
      const Stats::Totals interval = s.interval();
      nlohmann::ordered_json drops = nlohmann::ordered_json::object();
      const auto& rejects = host_.endpoint().rejects();
      for (std::size_t i = 0; i < protocol::kRejectCount; ++i) {
        const auto r = static_cast<protocol::Reject>(i);
        const std::uint64_t delta = rejects[r] - last_rejects_.counts[i];
        if (delta) drops[std::string(protocol::to_string(r))] = delta;
      }
      last_rejects_ = rejects;
      // Per session, the datagrams dropped since it started: over its rate, and sealed
      // ones that did not open (PROTOCOL.md 5.7). Only sessions with drops are listed.
      nlohmann::ordered_json session_drops = nlohmann::ordered_json::object();
      for (const auto& info : host_.endpoint().sessions()) {
        if (info.rate_limited + info.sealed_drops.total() == 0) continue;
        session_drops[std::to_string(info.player_id)] = {{"rate_limited", info.rate_limited},
                                                         {"forged", info.sealed_drops.forged},
                                                         {"replayed", info.sealed_drops.replayed}};
      }
      const InputTiming timing = host_.input_timing();
      log_record(spdlog::level::info, "stats",
                 {{"players", host_.endpoint().connected_players().size()},
                  {"tick", host_.match().tick}, {"rooms", host_.room_ids().size()},
                  {"tick_p50_us", p.p50_us}, {"tick_p99_us", p.p99_us}, {"tick_max_us", p.max_us},
                  {"ticks_skipped_total", clock_.skipped()},
                  {"datagrams_in", interval.datagrams_in}, {"datagrams_out", interval.datagrams_out},
                  {"bytes_in", interval.bytes_in}, {"bytes_out", interval.bytes_out},
                  {"send_errors", socket_.send_errors()}, {"drops", drops}, {"session_drops", session_drops},
                  // Input frames against the tick they named (PROTOCOL.md 4.5), in the open rooms.
                  {"inputs", {{"on_time", timing.on_time}, {"late", timing.late}, {"untimed", timing.untimed},
                              {"too_early", timing.too_early}, {"overflow", timing.overflow}}}});
      s.reset_interval();
      schedule_stats();
    });
  }

  const Options& options_;
  GameHost& host_;
  asio::io_context io_;
  UdpSocket socket_;
  asio::steady_timer tick_timer_;
  asio::steady_timer stats_timer_;
  asio::signal_set signals_;
  TickClock clock_;
  std::vector<protocol::Outgoing> datagrams_;   // reused by flush(): what the host queued
  std::vector<UdpSocket::Outgoing> outgoing_;  // reused by flush()
  std::int64_t epoch_ns_ = 0;
  std::int64_t last_skip_log_ns_ = 0;
  protocol::RejectCounters last_rejects_;
  std::unique_ptr<Fleet> fleet_;
  std::unique_ptr<HandoverChannel> handover_;  // --fleet-secret (issue 42); before io_ goes
  std::unique_ptr<ConsoleServer> console_;
  bool stopping_ = false;
  bool handed_over_all_ = false;  // every room offered to a peer once (hand_over "all")
};

}  // namespace

int run_udp_server(const Options& options, GameHost& host) {
  Loop loop(options, host);
  return loop.run();
}

}  // namespace fts::server
