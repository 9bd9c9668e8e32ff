// fts-bot: K scripted bot clients in one process (K sockets), for integration and load
// tests, and `--probe` as a health check. The only Asio translation unit of fts-bot.
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "bot/bot.hpp"
#include "fts/io/address.hpp"
#include "fts/io/udp.hpp"

namespace {

namespace asio = fts::io::asio;
using fts::io::udp;

constexpr const char* kUsage =
    "usage: fts-bot --connect HOST:PORT [--name N] [--count K] [--behavior idle|wander|hunter|shopper]\n"
    "               [--script FILE] [--duration S] [--encoding json|msgpack] [--seed S]\n"
    "               [--token T] [--token-file F] [--report FILE|-] [--room CODE|quick|create] [--spectate CODE]\n"
    "--room: quick (default) plays in the fullest open public room or a new one; create makes a private\n"
    "room for all K bots (the first creates it, the others join its code); CODE joins that room.\n"
    "--spectate CODE: watch that room (no ball, no seat).\n"
    "--predict: predict the own ball as fts-client does and stamp frames with their tick (PROTOCOL.md\n"
    "4.5.1); the report then has the corrections (load tests cover the client's CPU).\n"
    "--token-file F: read the session token from F if it exists, and write it there once welcomed\n"
    "(so a killed bot started again takes its player back within the reconnect window).\n"
    "       fts-bot --probe HOST:PORT      connect, wait for one snapshot, exit 0 (or 1 with the reason) within 2 s\n"
    "With --count K the bots are named N1..NK. The report (default: stdout) is a JSON array, one object per bot.\n"
    "Exit status: 0 when every bot succeeded, 1 when one failed (a failed expect, a deadline, a refusal), 2 on bad usage.\n";

int usage(const std::string& m) {
  std::cerr << "fts-bot: " << m << "\n" << kUsage;
  return 2;
}

struct Args {
  std::string host, port, name = "bot", script_path, report = "-", token, token_file;
  std::uint16_t protocol_version = 0;
  int count = 1;
  double duration_s = 0;  // 0: until the script ends (or forever without one)
  fts::bot::Behavior behavior = fts::bot::Behavior::hunter;
  fts::protocol::Encoding encoding = fts::protocol::Encoding::msgpack;
  std::uint64_t seed = 1;
  bool probe = false;
  bool predict = false;
  std::string join, room;  // Hello::join and Hello::room
};

std::optional<std::string> parse_args(int argc, char** argv, Args& a) {
  // Each value flag and the message for a missing value.
  const std::pair<const char*, const char*> flags[] = {
      {"--connect", "--connect needs HOST:PORT"}, {"--probe", "--probe needs HOST:PORT"},
      {"--name", "--name needs 1..12 characters"}, {"--count", "--count needs a number"},
      {"--behavior", "--behavior needs a value"}, {"--script", "--script needs a file"},
      {"--duration", "--duration needs seconds"}, {"--encoding", "--encoding must be json or msgpack"},
      {"--seed", "--seed needs a number"}, {"--token", "--token needs a value"},
      {"--token-file", "--token-file needs a file"},
      {"--room", "--room needs CODE, quick or create"}, {"--spectate", "--spectate needs a room code"},
      {"--protocol-version", "--protocol-version needs a number"},  // for tests of the server's version refusal
      {"--report", "--report needs a file or -"}};
  CLI::App app{"", "fts-bot"};
  app.set_help_flag();
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  const CLI::Option* help = app.add_flag("-h,--help");
  const CLI::Option* predict = app.add_flag("--predict");
  for (const auto& f : flags) app.add_option(f.first);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ArgumentMismatch&) {
    // Only a flag at the very end lacks its value (any next argument is taken).
    const std::string flag = std::string(argv[argc - 1]).substr(0, std::string(argv[argc - 1]).find('='));
    for (const auto& [name, message] : flags)
      if (flag == name) return std::string(message);
    return flag + " needs a value";
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  if (help->count() > 0) return std::string("help");
  a.predict = predict->count() > 0;
  if (!app.remaining().empty()) return "unknown flag " + app.remaining().front();
  auto value = [&](const std::string& flag) -> std::optional<std::string> {
    const CLI::Option* o = app.get_option(flag);
    if (o->count() == 0) return std::nullopt;
    return o->results().back();
  };
  for (const char* flag : {"--connect", "--probe"}) {
    const auto v = value(flag);
    if (!v) continue;
    const auto hp = fts::io::parse_host_port(*v);
    if (!hp) return std::string(flag) + " needs HOST:PORT";
    a.host = hp->host;
    a.port = hp->port;
    a.probe = std::string(flag) == "--probe";
  }
  if (const auto v = value("--name")) {
    if (v->empty() || v->size() > 12) return std::string("--name needs 1..12 characters");
    a.name = *v;
  }
  if (const auto v = value("--count")) {
    a.count = std::atoi(v->c_str());
    if (a.count < 1 || a.count > 256) return "--count must be 1..256, got " + *v;
  }
  if (const auto v = value("--behavior")) {
    auto b = fts::bot::parse_behavior(*v);
    if (!b) return "--behavior must be idle, wander, hunter or shopper, got " + *v;
    a.behavior = *b;
  }
  if (const auto v = value("--script")) a.script_path = *v;
  if (const auto v = value("--duration")) {
    char* end = nullptr;
    a.duration_s = std::strtod(v->c_str(), &end);
    if (*end || a.duration_s <= 0) return "--duration must be seconds > 0, got " + *v;
  }
  if (const auto v = value("--encoding")) {
    if (*v != "json" && *v != "msgpack") return std::string("--encoding must be json or msgpack");
    a.encoding = *v == "json" ? fts::protocol::Encoding::json : fts::protocol::Encoding::msgpack;
  }
  if (const auto v = value("--seed")) a.seed = std::strtoull(v->c_str(), nullptr, 10);
  if (const auto v = value("--token")) a.token = *v;
  if (const auto v = value("--token-file")) a.token_file = *v;
  if (const auto v = value("--protocol-version")) a.protocol_version = static_cast<std::uint16_t>(std::atoi(v->c_str()));
  if (const auto v = value("--report")) a.report = *v;
  if (const auto v = value("--room")) {
    if (*v == "quick" || *v == "create") {
      a.join = *v;
    } else if (v->size() == 5) {
      a.join = "join";
      a.room = *v;
    } else {
      return "--room must be quick, create or a 5-letter room code, got " + *v;
    }
  }
  if (const auto v = value("--spectate")) {
    if (!a.join.empty()) return std::string("--spectate and --room exclude each other");
    if (v->size() != 5) return "--spectate needs a 5-letter room code, got " + *v;
    a.join = "spectate";
    a.room = *v;
  }
  if (a.host.empty()) return std::string("--connect HOST:PORT (or --probe HOST:PORT) is required");
  return std::nullopt;
}

// One bot and its socket; each connection attempt of the bot gets a fresh socket.
struct Slot {
  Slot(asio::io_context& io, fts::bot::BotOptions o) : socket(io), bot(std::move(o)) {}
  fts::io::UdpSocket socket;
  fts::bot::Bot bot;
  std::uint64_t socket_attempt = 0;
};

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (auto err = parse_args(argc, argv, a)) {
    if (*err == "help") {
      std::cout << kUsage;
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

  const auto t0 = std::chrono::steady_clock::now();
  auto now_ms = [&] {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count());
  };
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
    o.protocol_version = a.protocol_version;
    o.join = join;
    o.room = room;
    slots.push_back(std::make_unique<Slot>(io, std::move(o)));
    slots.back()->bot.start(now_ms());
  };
  for (int i = 0; i < first_wave; ++i) make_slot(i, a.join, a.room);

  // A new connection attempt (the bot's reconnect) sends from a fresh local port.
  auto open_socket = [&](Slot& s) -> bool {
    s.socket_attempt = s.bot.attempt();
    if (const auto ec = s.socket.connect(server)) {
      std::cerr << "fts-bot: cannot open a socket: " << ec.message() << "\n";
      return false;
    }
    s.socket.start_receiving([&, sp = &s](const udp::endpoint&, std::span<const std::uint8_t> bytes) {
      sp->bot.receive(bytes, now_ms());
    });
    return true;
  };
  auto flush = [&](Slot& s) {
    if (s.bot.attempt() != s.socket_attempt && !open_socket(s)) return;
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
