#include "client_options.hpp"

#include <cstdlib>
#include <iostream>
#include <variant>

#include <CLI/CLI.hpp>

#include "fts/io/address.hpp"
#include "fts/protocol/constants.hpp"
#include "ui/sanitize.hpp"
#include "ui/screen.hpp"

namespace fts::client {
namespace proto = fts::protocol;

namespace {

constexpr const char* kUsage =
    "Usage: fts-client --connect HOST:PORT --name NAME [options]\n"
    "       fts-client --replay PATH\n"
    "\n"
    "Plays Fear The Sphere in this terminal against an fts-server.\n"
    "\n"
    "Options:\n"
    "  --connect HOST:PORT     the server (e.g. 127.0.0.1:7777)\n"
    "  --name NAME             your name: 1 to 16 printable ASCII characters\n"
  "  --name-file PATH        or the name kept in PATH (asked for and saved there when it\n"
  "                          holds none; cleaned of control and non-ASCII characters)\n"
    "  --encoding json|msgpack wire encoding (default msgpack)\n"
    "  --interp-delay-ms N     draw other balls this far behind the server, fixed (default:\n"
    "                          adaptive, from the measured jitter and loss of snapshots)\n"
    "  --no-predict            draw your own ball from snapshots too (no prediction)\n"
    "  --stats-file PATH       at exit, write the link and prediction figures (JSON)\n"
    "  --fps N                 frames drawn per second (default 60)\n"
    "  --no-kitty              do not ask the terminal for key release events\n"
    "  --no-mouse              do not steer with the mouse (no mouse reporting)\n"
    "  --glyphs auto|braille|ascii  the field in braille dots (finer: needs UTF-8 and\n"
    "                          colour) or in ASCII; auto (default) picks braille when the\n"
    "                          locale is UTF-8 and TERM is not dumb, linux or vt*\n"
    "  --replay PATH           play back a server record (fts-server --record PATH):\n"
    "                          Space pauses, - and + set the speed (x0.5 to x8), n/p go\n"
    "                          to the next/previous level, 1-9 to a level, e to the end\n"
    "  --new                   start a new player (default: take back the player of the\n"
    "                          last session on this server, kept in $XDG_STATE_HOME)\n"
    "  --quick                 quick play: the fullest open room, or a new one\n"
    "  --create                create a private room; friends join with the code in the HUD\n"
    "  --join CODE             join the room with this code\n"
    "  --spectate CODE         watch the room with this code\n"
    "                          (none of these: a start screen asks)\n"
    "  --idle-exit-s N         end the session after N s without a key (exit status 3;\n"
  "                          default 0: never), at the prompts and in the game\n"
  "  --help                  this text\n"
    "\n"
    "Controls: arrows, WASD or hjkl thrust (a tap is a short push, holding keeps pushing),\n"
    "the mouse pointer steers (the ball thrusts toward it; a click fires), space fires\n"
    "rockets, m s a r l x b buy in the shop, Enter is ready (and play again), t opens a\n"
    "chat line (Enter sends, Esc cancels), Tab follows another player while you watch,\n"
    "q twice quits. NO_COLOR=1 turns colours off.\n";


int usage_error(const std::string& msg) {
  std::cerr << "fts-client: " << msg << "\n(see fts-client --help)\n";
  return 2;
}

}  // namespace

protocol::ClientConfig connection_config(const Options& o, std::optional<std::string> saved_token) {
  protocol::ClientConfig cfg;
  cfg.name = o.name;
  cfg.encoding = o.encoding;
  if (o.room) {
    cfg.join = o.room->join;
    cfg.room = o.room->room;
  }
  if (saved_token) cfg.token = std::move(*saved_token);
  return cfg;
}

bool idle_over(const Options& o, std::uint64_t idle_ms) {
  return o.idle_exit_s > 0 && idle_ms > static_cast<std::uint64_t>(o.idle_exit_s) * 1000;
}

std::string idle_text(const Options& o) { return "no key for " + std::to_string(o.idle_exit_s) + " s: goodbye"; }

bool fine_field(const Options& o) {
  if (o.glyphs != "auto") return o.glyphs == "braille";
  return braille_wanted(std::getenv("LC_ALL"), std::getenv("LC_CTYPE"), std::getenv("LANG"), std::getenv("TERM"));
}

int parse_options(int argc, char** argv, Options& o) {
  CLI::App app{"", "fts-client"};
  app.set_help_flag();
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  const CLI::Option* help = app.add_flag("-h,--help");
  const CLI::Option* no_kitty = app.add_flag("--no-kitty");
  const CLI::Option* no_mouse = app.add_flag("--no-mouse");
  const CLI::Option* fresh = app.add_flag("--new");
  const CLI::Option* quick = app.add_flag("--quick");
  const CLI::Option* create = app.add_flag("--create");
  const CLI::Option* no_predict = app.add_flag("--no-predict");
  for (const char* flag : {"--connect", "--name", "--encoding", "--interp-delay-ms", "--fps", "--replay", "--join", "--spectate",
                           "--stats-file", "--name-file", "--idle-exit-s", "--glyphs"})
    app.add_option(flag);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ArgumentMismatch&) {
    return usage_error("unknown or incomplete option '" + std::string(argv[argc - 1]) + "'");
  } catch (const CLI::ParseError& e) {
    return usage_error(e.what());
  }
  if (help->count() > 0) {
    std::cout << kUsage;
    return 0;
  }
  if (!app.remaining().empty()) return usage_error("unknown or incomplete option '" + app.remaining().front() + "'");
  auto value = [&](const std::string& flag) -> std::optional<std::string> {
    const CLI::Option* opt = app.get_option(flag);
    if (opt->count() == 0) return std::nullopt;
    return opt->results().back();
  };
  o.kitty = no_kitty->count() == 0;
  o.mouse = no_mouse->count() == 0;
  o.fresh = fresh->count() > 0;
  o.predict = no_predict->count() == 0;
  if (const auto v = value("--stats-file")) {
    if (v->empty()) return usage_error("--stats-file needs a path");
    o.stats_file = *v;
  }
  if (const auto v = value("--connect")) {
    const auto hp = fts::io::parse_host_port(*v);
    if (!hp) return usage_error("--connect wants HOST:PORT, got '" + *v + "'");
    o.host = hp->host;
    o.port = hp->port;
  }
  if (const auto v = value("--name")) o.name = *v;
  if (const auto v = value("--encoding")) {
    if (*v == "json") o.encoding = proto::Encoding::json;
    else if (*v == "msgpack") o.encoding = proto::Encoding::msgpack;
    else return usage_error("--encoding is json or msgpack, got '" + *v + "'");
  }
  // The numeric options: flag, range, where the value goes.
  struct Numeric {
    const char* flag;
    long min, max;
    void (*store)(Options&, int);
  };
  static constexpr Numeric kNumeric[] = {
      {"--fps", 1, 240, [](Options& x, int n) { x.fps = n; }},
      {"--interp-delay-ms", 0, 2000, [](Options& x, int n) { x.interp_delay_ms = n; }},
      {"--idle-exit-s", 0, 86400, [](Options& x, int n) { x.idle_exit_s = n; }},
  };
  for (const Numeric& num : kNumeric) {
    const auto v = value(num.flag);
    if (!v) continue;
    char* end = nullptr;
    const long n = std::strtol(v->c_str(), &end, 10);
    if (end == v->c_str() || *end != '\0' || n < num.min || n > num.max)
      return usage_error(std::string(num.flag) + " is " + std::to_string(num.min) + ".." + std::to_string(num.max) +
                         ", got '" + *v + "'");
    num.store(o, static_cast<int>(n));
  }
  if (const auto v = value("--glyphs")) {
    if (*v != "auto" && *v != "braille" && *v != "ascii")
      return usage_error("--glyphs is auto, braille or ascii, got '" + *v + "'");
    o.glyphs = *v;
  }
  if (const auto v = value("--name-file")) {
    if (v->empty()) return usage_error("--name-file needs a path");
    o.name_file = *v;
  }
  if (const auto v = value("--replay")) {
    if (v->empty()) return usage_error("--replay needs a record file");
    o.replay = *v;
    return -1;
  }
  const int room_flags = static_cast<int>(quick->count() > 0) + static_cast<int>(create->count() > 0) +
                         static_cast<int>(value("--join").has_value()) + static_cast<int>(value("--spectate").has_value());
  if (room_flags > 1) return usage_error("--quick, --create, --join and --spectate exclude each other");
  if (quick->count() > 0) o.room = RoomChoice{};
  if (create->count() > 0) o.room = RoomChoice{"create", ""};
  for (const char* flag : {"--join", "--spectate"}) {
    const auto v = value(flag);
    if (!v) continue;
    const auto choice = parse_start_choice(std::string(flag == std::string("--join") ? "3 " : "4 ") + *v);
    if (const auto* why = std::get_if<std::string>(&choice)) return usage_error(std::string(flag) + ": " + *why);
    o.room = std::get<RoomChoice>(choice);
  }
  if (o.host.empty()) return usage_error("--connect HOST:PORT is required");
  if (o.name.empty() && !o.name_file.empty()) return -1;  // main asks or reads the file
  if (o.name.empty() || o.name.size() > proto::kMaxNameBytes || sanitize(o.name) != o.name)
    return usage_error("--name must be 1 to 16 printable ASCII characters");
  return -1;
}

}  // namespace fts::client
