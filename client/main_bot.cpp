// fts-bot: K scripted bot clients in one process (K sockets), for integration and load
// tests, and `--probe` as a health check. The only Asio translation unit of fts-bot.
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "bot/bot.hpp"
#include "net/identity_store.hpp"
#include "option_checks.hpp"
#include "fts/io/address.hpp"
#include "fts/io/client_socket.hpp"
#include "fts/io/udp.hpp"

namespace {

namespace asio = fts::io::asio;
using fts::io::udp;

struct Args {
  std::string connect, probe_address;  // --connect / --probe HOST:PORT
  std::string name = "bot", script_path, report = "-", token, token_file, identity_file;
  std::uint16_t protocol_version = 0;
  int count = 1;
  double duration_s = 0;  // 0: until the script ends (or forever without one)
  fts::bot::Behavior behavior = fts::bot::Behavior::hunter;
  fts::protocol::Encoding encoding = fts::protocol::Encoding::msgpack;
  std::uint64_t seed = 1;
  bool predict = false;
  bool predict_own_only = false;
  fts::client::RemotePlayers predict_remote = fts::client::kDefaultRemotePlayers;
  std::string room_arg, spectate;  // --room, --spectate
  std::string source;              // --source: the local address to send from
  // Made from the above: the server, whether this is a probe, Hello::join and Hello::room.
  std::string host, port;
  bool probe = false;
  std::string join, room;
};

bool parse_name(const std::string& text, std::string& out) {
  if (text.empty() || text.size() > 12) return false;
  out = text;
  return true;
}
bool parse_behavior(const std::string& text, fts::bot::Behavior& out) {
  const auto b = fts::bot::parse_behavior(text);
  if (b) out = *b;
  return b.has_value();
}
std::string show_behavior(const fts::bot::Behavior& b) {
  constexpr const char* names[] = {"idle", "wander", "hunter", "shopper"};
  return names[static_cast<int>(b)];
}
bool parse_duration(const std::string& text, double& out) {
  double v = 0;
  if (!fts::cli::parse_real(text, v) || !(v > 0)) return false;
  out = v;
  return true;
}
std::string show_duration(const double& v) { return v > 0 ? fts::cli::show_real(v) : "0 (until the script ends)"; }
bool parse_room(const std::string& text, std::string& out) {
  if (text != "quick" && text != "create" && text.size() != 5) return false;
  out = text;
  return true;
}
bool parse_remote(const std::string& text, fts::client::RemotePlayers& out) {
  if (text == "held") out = fts::client::RemotePlayers::held;
  else if (text == "coast") out = fts::client::RemotePlayers::coast;
  else if (text == "off") out = fts::client::RemotePlayers::off;
  else return false;
  return true;
}
std::string show_remote(const fts::client::RemotePlayers& r) {
  return r == fts::client::RemotePlayers::held ? "held" : r == fts::client::RemotePlayers::coast ? "coast" : "off";
}
bool parse_code(const std::string& text, std::string& out) {
  if (text.size() != 5) return false;
  out = text;
  return true;
}

using fts::cli::Int, fts::cli::Text, fts::cli::Custom;
using fts::client::show_text;
constexpr Custom<std::string> kName{parse_name, show_text, "1..12 characters"};
constexpr Custom<fts::bot::Behavior> kBehavior{parse_behavior, show_behavior, "idle, wander, hunter, shopper"};
constexpr Custom<double> kDuration{parse_duration, show_duration, "seconds > 0"};
constexpr Custom<std::string> kRoom{parse_room, show_text, "quick, create, a 5-letter code"};
constexpr Custom<std::string> kCode{parse_code, show_text, "a 5-letter code"};
bool parse_ip(const std::string& text, std::string& out) {
  if (!fts::io::is_ip_address(text)) return false;
  out = text;
  return true;
}
constexpr Custom<std::string> kIp{parse_ip, show_text, "an IP address"};
constexpr Custom<fts::client::RemotePlayers> kRemote{parse_remote, show_remote, "held, coast, off"};

inline constexpr auto kOptionTable = std::tuple{
    fts::cli::value("--connect", "", &Args::connect, fts::client::kHostPort, "needs HOST:PORT", "the server",
                    "HOST:PORT"),
    fts::cli::value("--probe", "", &Args::probe_address, fts::client::kHostPort, "needs HOST:PORT",
                    "health check: connect, wait for one snapshot, exit 0 (or 1 with the reason) within 2 s",
                    "HOST:PORT"),
    fts::cli::value("--name", "", &Args::name, kName, "needs 1..12 characters",
                    "the bot's name; with --count K the bots are named N1..NK", "N"),
    fts::cli::value("--count", "", &Args::count, Int<int>{1, 256}, "must be 1..256", "bots in this process (K sockets)",
                    "K"),
    fts::cli::value("--behavior", "", &Args::behavior, kBehavior, "must be idle, wander, hunter or shopper",
                    "how the bots play", "idle|wander|hunter|shopper"),
    fts::cli::value("--script", "", &Args::script_path, Text{}, "needs a file",
                    "a script of steps and expectations (docs/testing.md)", "FILE"),
    fts::cli::value("--duration", "", &Args::duration_s, kDuration, "must be seconds > 0",
                    "stop after this long (s)", "S"),
    fts::cli::value("--encoding", "", &Args::encoding, fts::client::kEncoding, "must be json or msgpack",
                    "wire encoding", "json|msgpack"),
    fts::cli::value("--seed", "", &Args::seed, Int<std::uint64_t>{0, UINT64_MAX}, "needs a number",
                    "the first bot's random seed (bot i: seed + i)", "S"),
    fts::cli::value("--token", "", &Args::token, Text{}, "needs a value", "the first bot's session token", "T"),
    fts::cli::value("--token-file", "", &Args::token_file, Text{}, "needs a file",
                    "read the session token from F if it exists, and write it there once welcomed (so a killed bot "
                    "started again takes its player back within the reconnect window)",
                    "F"),
    fts::cli::value("--identity", "", &Args::identity_file, Text{}, "needs a file",
                    "play with the identity in F (PROTOCOL.md 5.8; made if missing, mode 0600); with --count K, bot "
                    "k > 1 uses F.k. Without it a bot is a guest",
                    "F"),
    fts::cli::value("--report", "", &Args::report, Text{true}, "needs a file or -",
                    "where the report goes: a JSON array, one object per bot (-: stdout)", "FILE"),
    fts::cli::value("--room", "", &Args::room_arg, kRoom, "must be quick, create or a 5-letter room code",
                    "quick (the default) plays in the fullest open public room or a new one; "
                    "create makes a private room for all K bots (the first creates it, the others join its code); "
                    "CODE joins that room",
                    "CODE|quick|create"),
    fts::cli::value("--spectate", "", &Args::spectate, kCode, "needs a 5-letter room code",
                    "watch that room (no ball, no seat)", "CODE"),
    fts::cli::value("--source", "", &Args::source, kIp, "must be an IP address",
                    "send from this local address (load tests: each bot process a host of its own, 127.0.0.N)",
                    "ADDR"),
    fts::cli::on("--predict", "", &Args::predict,
                 "predict the own ball as fts-client does and stamp frames with their tick (PROTOCOL.md 4.5.1); the "
                 "report then has the corrections (load tests cover the client's CPU)"),
    fts::cli::on("--predict-own-only", "", &Args::predict_own_only,
                 "with --predict, step the own ball alone (no collisions predicted; the prediction before issue 37, "
                 "for benchmarks against it)"),
    fts::cli::value("--predict-remote", "", &Args::predict_remote, kRemote, "must be held, coast or off",
                    "with --predict, other players' balls near ours: stepped with the thrust their last snapshots "
                    "show held, coasting (the default, as fts-client), or left out",
                    "held|coast|off"),
    fts::cli::value("--protocol-version", "", &Args::protocol_version, Int<std::uint16_t>{0, 65535}, "needs a number",
                    "the protocol version the hello claims (0: this build's), for tests of the server's refusal", "N"),
};
static_assert(fts::fields::names_every_member<Args>(kOptionTable, &Args::host, &Args::port, &Args::probe, &Args::join,
                                                    &Args::room),
              "a member of Args has no row in kOptionTable");

constexpr fts::cli::Program kProgram{
    "fts-bot",
    "usage: fts-bot --connect HOST:PORT [options]\n"
    "       fts-bot --probe HOST:PORT\n",
    "Exit status: 0 when every bot succeeded, 1 when one failed (a failed expect, a deadline, a refusal), 2 on bad "
    "usage.\n",
    fts::cli::Wording{false, ""},
    false,
    false,
};

const std::vector<fts::cli::RowInfo>& rows() {
  static const std::vector<fts::cli::RowInfo> r = fts::cli::infos(kOptionTable);
  return r;
}

int usage(const std::string& m) {
  std::cerr << "fts-bot: " << m << "\n" << fts::cli::help_text(kProgram, rows());
  return 2;
}

// "help" and "markdown" for those flags.
std::optional<std::string> parse_args(int argc, char** argv, Args& a) {
  auto parsed = fts::cli::parse(kProgram, kOptionTable, a, std::vector<std::string>(argv + 1, argv + argc));
  if (const auto* e = std::get_if<fts::cli::Error>(&parsed)) return e->message;
  const auto& p = std::get<fts::cli::Parsed>(parsed);
  if (p.help) return std::string("help");
  if (p.markdown) return std::string("markdown");
  // --probe wins over --connect, as before.
  for (const bool probe : {false, true}) {
    const std::string& v = probe ? a.probe_address : a.connect;
    if (v.empty()) continue;
    const auto hp = fts::io::parse_host_port(v);
    a.host = hp->host;
    a.port = hp->port;
    a.probe = probe;
  }
  if (p.given.contains("room")) {
    // "quick" is five letters too: the words first, then a code.
    const bool word = a.room_arg == "quick" || a.room_arg == "create";
    a.join = word ? a.room_arg : "join";
    if (!word) a.room = a.room_arg;
  }
  if (p.given.contains("spectate")) {
    if (!a.join.empty()) return std::string("--spectate and --room exclude each other");
    a.join = "spectate";
    a.room = a.spectate;
  }
  if (a.host.empty()) return std::string("--connect HOST:PORT (or --probe HOST:PORT) is required");
  return std::nullopt;
}

// One bot and its socket; each connection attempt of the bot gets a fresh socket.
struct Slot {
  Slot(asio::io_context& io, fts::bot::BotOptions o, udp::endpoint to, std::optional<asio::ip::address> from)
      : socket(io, to, from), bot(std::move(o)) {}
  fts::io::ClientSocket socket;  // a fresh one per attempt, to where the room is
  fts::bot::Bot bot;
};

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (auto err = parse_args(argc, argv, a)) {
    if (*err == "help" || *err == "markdown") {
      std::cout << (*err == "help" ? fts::cli::help_text(kProgram, rows())
                                   : "# fts-bot flags\n\n<!-- Generated by `fts-bot --help-markdown` from "
                                     "client/main_bot.cpp; the test flags_docs fails when it differs. -->\n\n" +
                                         fts::cli::markdown(kProgram, rows(), "fts-bot"));
      return 0;
    }
    return usage(*err);
  }
  std::vector<fts::bot::Step> steps;
  if (!a.script_path.empty()) {
    std::ifstream in(a.script_path);
    if (!in) return usage("cannot read script " + a.script_path);
    std::stringstream text;
    text << in.rdbuf();
    auto parsed = fts::bot::parse_script(text.str());
    if (auto* e = std::get_if<std::string>(&parsed)) {
      std::cerr << "fts-bot: " << a.script_path << ": " << *e << "\n";
      return 2;
    }
    steps = std::get<std::vector<fts::bot::Step>>(parsed);
  }

  if (!a.token_file.empty() && a.token.empty()) {
    std::ifstream in(a.token_file);
    std::getline(in, a.token);
  }
  asio::io_context io;
  std::string why;
  const auto resolved = fts::io::resolve(io, a.host, a.port, why);
  if (!resolved) {
    std::cerr << "fts-bot: cannot resolve " << a.host << ":" << a.port << ": " << why << "\n";
    return a.probe ? 1 : 2;
  }
  const udp::endpoint server = *resolved;
  std::optional<asio::ip::address> source;
  if (!a.source.empty()) source = asio::ip::make_address(a.source);
  const auto t0 = std::chrono::steady_clock::now();
  auto now_ms = [&] {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count());
  };
  // Each bot's identity (--identity), read or made before the first connects.
  std::vector<std::optional<fts::protocol::Identity>> identities(static_cast<std::size_t>(a.count));
  if (!a.identity_file.empty()) {
    for (int i = 0; i < a.count; ++i) {
      const std::string path = i == 0 ? a.identity_file : a.identity_file + "." + std::to_string(i + 1);
      identities[static_cast<std::size_t>(i)] = fts::client::load_or_create_identity(path, why);
      if (!identities[static_cast<std::size_t>(i)]) {
        std::cerr << "fts-bot: " << why << "\n";
        return 2;
      }
    }
  }
  std::vector<std::unique_ptr<Slot>> slots;
  // --room create: the first bot makes the room, the others join its code once known.
  const int first_wave = a.join == "create" ? 1 : (a.probe ? 1 : a.count);
  auto make_slot = [&](int i, const std::string& join, const std::string& room) {
    fts::bot::BotOptions o;
    o.name = a.count > 1 ? a.name + std::to_string(i + 1) : a.name;
    o.behavior = a.probe ? fts::bot::Behavior::idle : a.behavior;
    o.script = steps;
    o.encoding = a.encoding;
    o.seed = a.seed + static_cast<std::uint64_t>(i);
    o.token = i == 0 ? a.token : "";
    o.probe = a.probe;
    o.predict = a.predict;
    o.predict_own_only = a.predict_own_only;
    o.predict_remote = a.predict_remote;
    o.protocol_version = a.protocol_version;
    o.join = join;
    o.room = room;
    o.identity = identities.at(static_cast<std::size_t>(i));
    slots.push_back(std::make_unique<Slot>(io, std::move(o), server, source));
    slots.back()->bot.start(now_ms());
  };
  for (int i = 0; i < first_wave; ++i) make_slot(i, a.join, a.room);

  // A new connection attempt (the bot's reconnect, or its room's move) sends from a fresh
  // local port, to where the room is.
  auto open_socket = [&](Slot& s) -> bool {
    const auto f = s.socket.follow(s.bot.attempt(), s.bot.moves(), s.bot.moved_to(),
                                   [&, sp = &s](const udp::endpoint&, std::span<const std::uint8_t> bytes) {
                                     sp->bot.receive(bytes, now_ms());
                                   });
    if (!f.error.empty()) std::cerr << "fts-bot: " << f.error << "\n";
    return f.error.empty() || f.opened;
  };
  auto flush = [&](Slot& s) {
    if (!open_socket(s)) return;
    for (auto& d : s.bot.take_datagrams()) s.socket.send(d);
  };
  for (auto& s : slots) {
    if (!open_socket(*s)) return 1;
    flush(*s);
  }
  bool second_wave_failed = false;

  const double limit_s = a.probe ? 2.0 : a.duration_s;
  bool stopping = false;
  bool token_written = false;
  asio::steady_timer timer(io);
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code& e, int) {
    if (e) return;
    for (auto& s : slots) {
      s->bot.stop(now_ms());
      flush(*s);
    }
    io.stop();
  });
  std::function<void()> tick = [&] {
    timer.expires_after(std::chrono::milliseconds(5));
    timer.async_wait([&](const boost::system::error_code& e) {
      if (e) return;
      bool all_done = true;
      for (auto& s : slots) {
        s->bot.update(now_ms());
        flush(*s);
        all_done = all_done && s->bot.finished();
      }
      if (static_cast<int>(slots.size()) < a.count && !a.probe) {
        all_done = false;
        if (!slots[0]->bot.room().empty()) {
          const std::string code = slots[0]->bot.room();
          for (int i = static_cast<int>(slots.size()); i < a.count; ++i) {
            make_slot(i, "join", code);
            if (!open_socket(*slots.back())) second_wave_failed = true;
            flush(*slots.back());
          }
        } else if (slots[0]->bot.finished()) {
          all_done = true;  // the room was never made: the first bot's report says why
        }
      }
      if (!a.token_file.empty() && !token_written && !slots[0]->bot.token().empty()) {
        std::ofstream(a.token_file) << slots[0]->bot.token() << "\n";
        token_written = true;
      }
      const bool out_of_time = limit_s > 0 && static_cast<double>(now_ms()) >= limit_s * 1000.0;
      if (all_done || out_of_time || stopping) {
        for (auto& s : slots) {
          if (!s->bot.finished() && a.probe) continue;
          s->bot.stop(now_ms());
          flush(*s);
        }
        io.stop();
        return;
      }
      tick();
    });
  };
  tick();
  io.run();

  if (a.probe) {
    const auto& bot = slots[0]->bot;
    if (!bot.failed() && bot.report()["snapshots_received"].get<std::uint64_t>() > 0) {
      std::cout << "ok: " << a.host << ":" << a.port << " answered with a snapshot\n";
      return 0;
    }
    std::cerr << "fts-bot: probe of " << a.host << ":" << a.port << " failed: "
              << (bot.failed() ? bot.failure() : std::string("no snapshot within 2 s")) << "\n";
    return 1;
  }
  nlohmann::ordered_json report = nlohmann::ordered_json::array();
  bool ok = true;
  for (auto& s : slots) {
    report.push_back(s->bot.report());
    ok = ok && !s->bot.failed();
    if (s->bot.failed()) std::cerr << "fts-bot: " << report.back()["name"].get<std::string>() << ": " << s->bot.failure() << "\n";
  }
  if (a.report == "-") {
    std::cout << report.dump(2) << "\n";
  } else {
    std::ofstream out(a.report);
    out << report.dump(2) << "\n";
    if (!out) {
      std::cerr << "fts-bot: cannot write " << a.report << "\n";
      return 1;
    }
  }
  return ok && !second_wave_failed ? 0 : 1;
}
