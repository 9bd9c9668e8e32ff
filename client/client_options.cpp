#include "client_options.hpp"

#include <cstdlib>
#include <iostream>
#include <variant>

#include "fts/io/address.hpp"
#include "option_checks.hpp"
#include "fts/protocol/constants.hpp"
#include "ui/sanitize.hpp"
#include "ui/screen.hpp"

namespace fts::client {
namespace proto = fts::protocol;

namespace {

using cli::Int, cli::Text;

// One row per member of Options, but those made from others (host, port, room).
inline constexpr auto kOptionTable = std::tuple{
    cli::value("--connect", "", &Options::connect, kHostPort, "wants HOST:PORT", "the server (e.g. 127.0.0.1:7777)",
               "HOST:PORT"),
    cli::value("--name", "", &Options::name, Text{}, "must be a name", "your name: 1 to 16 printable ASCII characters",
               "NAME"),
    cli::value("--name-file", "", &Options::name_file, Text{true}, "needs a path",
               "or the name kept in PATH (asked for and saved there when it holds none; cleaned of control and "
               "non-ASCII characters); --name wins over it",
               "PATH"),
    cli::value("--encoding", "", &Options::encoding, kEncoding, "is json or msgpack", "wire encoding", "json|msgpack"),
    cli::value("--interp-delay-ms", "", &Options::interp_delay_ms, cli::Maybe<Int<int>>{{0, 2000}}, "is 0..2000",
               "draw other balls this far behind the server, fixed (default: adaptive, from the measured jitter and "
               "loss of snapshots)",
               "N"),
    cli::off("--no-predict", &Options::predict, "draw your own ball from snapshots too (no prediction)"),
    cli::value("--stats-file", "", &Options::stats_file, Text{true}, "needs a path",
               "every second and at exit, write the link and prediction figures (JSON)", "PATH"),
    cli::value("--fps", "", &Options::fps, Int<int>{1, 240}, "is 1..240", "frames drawn per second", "N"),
    cli::off("--no-kitty", &Options::kitty, "do not ask the terminal for key release events"),
    cli::off("--no-mouse", &Options::mouse, "do not steer with the mouse (no mouse reporting)"),
    cli::value("--glyphs", "", &Options::glyphs, cli::OneOf{{"auto", "braille", "ascii"}}, "is auto, braille or ascii",
               "the field in braille dots (finer: needs UTF-8 and colour) or in ASCII; auto picks braille when the "
               "locale is UTF-8 and TERM is not dumb, linux or vt*",
               "auto|braille|ascii"),
    cli::value("--replay", "", &Options::replay, Text{true}, "needs a record",
               "play back a server record (fts-server --record DIR): Space pauses, - and + set the speed (x0.5 to x8), "
               "n/p go to the next/previous level, 1-9 to a level, e to the end",
               "PATH"),
    cli::on("--new", "", &Options::fresh,
            "start a new player (default: take back the player of the last session on this server, kept in "
            "$XDG_STATE_HOME)"),
    cli::on("--quick", "", &Options::quick, "quick play: the fullest open room, or a new one"),
    cli::on("--create", "", &Options::create, "create a private room; friends join with the code in the HUD"),
    cli::value("--join", "", &Options::join, Text{}, "needs a room code", "join the room with this code", "CODE"),
    cli::value("--spectate", "", &Options::spectate, Text{}, "needs a room code",
               "watch the room with this code (none of these four: a start screen asks)", "CODE"),
    cli::value("--idle-exit-s", "", &Options::idle_exit_s, Int<int>{0, 86400}, "is 0..86400",
               "end the session after N s without a key (exit status 3; 0: never), at the prompts and in the game",
               "N"),
    cli::value("--identity", "", &Options::identity_file, Text{true}, "needs a file",
               "your identity, a key kept like an ssh key (default $XDG_STATE_HOME/fear-the-sphere/identity, made on "
               "the first run, mode 0600): a server with profiles keeps your records under it (PROTOCOL.md 5.8)",
               "FILE"),
    cli::on("--guest", "", &Options::guest, "play without an identity: nothing is recorded"),
    cli::on("--forget-me", "", &Options::forget_me,
            "erase your profile on the server (your records and your place on its leaderboard), after you type yes; "
            "your identity file is kept (delete it yourself to become someone new)"),
    cli::on("--yes", "", &Options::yes, "with --forget-me: do not ask, erase (for scripts)"),
};
static_assert(fields::names_every_member<Options>(kOptionTable, &Options::host, &Options::port, &Options::room,
                                                  &Options::identity),
              "a member of fts::client::Options has no row in kOptionTable");

constexpr cli::Program kProgram{
    "fts-client",
    "Usage: fts-client --connect HOST:PORT --name NAME [options]\n"
    "       fts-client --replay PATH\n"
    "       fts-client --connect HOST:PORT --forget-me [--yes]\n"
    "\n"
    "Plays Fear The Sphere in this terminal against an fts-server.\n",
    "Controls: arrows, WASD or hjkl thrust (a tap is a short push, holding keeps pushing),\n"
    "the mouse pointer steers (the ball thrusts toward it; a click fires), space fires\n"
    "rockets, m s a r l x b buy in the shop, Enter is ready (and play again), t opens a\n"
    "chat line (Enter sends, Esc cancels), Tab follows another player while you watch,\n"
    "q twice quits. NO_COLOR=1 turns colours off.\n",
    cli::Wording{false, "'"},
    false,
    false,
};

int usage_error(const std::string& msg) {
  std::cerr << "fts-client: " << msg << "\n(see fts-client --help)\n";
  return 2;
}

const std::vector<cli::RowInfo>& rows() {
  static const std::vector<cli::RowInfo> r = cli::infos(kOptionTable);
  return r;
}

}  // namespace

std::string usage_text() { return cli::help_text(kProgram, rows()); }

std::string markdown_text() {
  return "# fts-client flags\n\n"
         "<!-- Generated by `fts-client --help-markdown` from client/client_options.cpp; the test flags_docs "
         "fails when it differs. -->\n\n" +
         cli::markdown(kProgram, rows(), "fts-client");
}

protocol::ClientConfig connection_config(const Options& o, std::optional<std::string> saved_token) {
  protocol::ClientConfig cfg;
  cfg.name = o.name;
  cfg.encoding = o.encoding;
  if (o.room) {
    cfg.join = o.room->join;
    cfg.room = o.room->room;
  }
  if (saved_token) cfg.token = std::move(*saved_token);
  cfg.identity = o.identity;
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
  auto parsed = cli::parse(kProgram, kOptionTable, o, std::vector<std::string>(argv + 1, argv + argc));
  if (const auto* e = std::get_if<cli::Error>(&parsed)) return usage_error(e->message);
  const auto& p = std::get<cli::Parsed>(parsed);
  if (p.help || p.markdown) {
    std::cout << (p.help ? usage_text() : markdown_text());
    return 0;
  }
  if (!o.connect.empty()) {
    const auto hp = fts::io::parse_host_port(o.connect);
    o.host = hp->host;
    o.port = hp->port;
  }
  if (!o.replay.empty()) return -1;
  if (o.guest && p.given.contains("identity")) return usage_error("--identity and --guest exclude each other");
  const int room_flags = static_cast<int>(o.quick) + static_cast<int>(o.create) +
                         static_cast<int>(p.given.contains("join")) + static_cast<int>(p.given.contains("spectate"));
  if (room_flags > 1) return usage_error("--quick, --create, --join and --spectate exclude each other");
  if (o.quick) o.room = RoomChoice{};
  if (o.create) o.room = RoomChoice{"create", ""};
  for (const char* flag : {"join", "spectate"}) {
    if (!p.given.contains(flag)) continue;
    const std::string& code = flag == std::string("join") ? o.join : o.spectate;
    const auto choice = parse_start_choice(std::string(flag == std::string("join") ? "3 " : "4 ") + code);
    if (const auto* why = std::get_if<std::string>(&choice)) return usage_error("--" + std::string(flag) + ": " + *why);
    o.room = std::get<RoomChoice>(choice);
  }
  if (o.yes && !o.forget_me) return usage_error("--yes goes with --forget-me");
  if (o.forget_me && o.guest) return usage_error("--forget-me erases your identity's profile: not with --guest");
  if (o.forget_me && room_flags > 0) return usage_error("--forget-me joins no room: not with --quick, --create, --join or --spectate");
  if (o.host.empty()) return usage_error("--connect HOST:PORT is required");
  if (o.forget_me) {
    // It plays nothing: a name only for the handshake, unless one is given.
    if (o.name.empty()) o.name = "forget-me";
    if (o.name.size() > proto::kMaxNameBytes || sanitize(o.name) != o.name)
      return usage_error("--name must be 1 to 16 printable ASCII characters");
    o.room = RoomChoice{};
    return -1;
  }
  if (o.name.empty() && !o.name_file.empty()) return -1;  // main asks or reads the file
  if (o.name.empty() || o.name.size() > proto::kMaxNameBytes || sanitize(o.name) != o.name)
    return usage_error("--name must be 1 to 16 printable ASCII characters");
  return -1;
}

}  // namespace fts::client
