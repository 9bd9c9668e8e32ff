// fts-client's command line: the options (defaults: the member initialisers), and their
// table (flag, member, check, help) in client_options.cpp, from which the command line,
// --help and docs/flags/fts-client.md come.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fts/protocol/client.hpp"
#include "fts/protocol/constants.hpp"
#include "ui/start_screen.hpp"

namespace fts::client {

struct Options {
  std::string connect;     // --connect HOST:PORT, split into host and port
  std::string host, port;  // from connect
  std::string name;
  protocol::Encoding encoding = protocol::Encoding::msgpack;
  // Remote balls' delay behind the server clock: adaptive (a jitter buffer) unless this
  // is set (--interp-delay-ms N: fixed).
  std::optional<int> interp_delay_ms;
  bool predict = true;     // --no-predict: the own ball is drawn from snapshots too
  std::string stats_file;  // --stats-file PATH: the link and prediction figures, every second and at exit (JSON)
  int fps = 60;
  bool kitty = true;
  bool mouse = true;  // --no-mouse: no mouse reporting, keys only
  bool fresh = false;  // --new: ignore the saved session token
  std::string replay;  // --replay FILE: play a record back, no server
  // --quick, --create, --join CODE, --spectate CODE: the room, none of them: the start
  // screen asks.
  bool quick = false;
  bool create = false;
  std::string join, spectate;
  std::optional<RoomChoice> room;  // from the four above
  // --name-file PATH: the name kept there (a host's ssh gate keeps one per key); asked
  // for once when the file has none, and saved. --name wins over it.
  std::string name_file;
  // --idle-exit-s N: with no key for N s (at a prompt or in the game) the client ends
  // with kIdleExitCode; 0: never (the server's own idle kick is another matter).
  int idle_exit_s = 0;
  // --glyphs auto|braille|ascii: the field in braille dots or in ASCII; auto asks the
  // locale and TERM (braille_wanted).
  std::string glyphs = "auto";
  // The player's identity (PROTOCOL.md 5.8): --identity FILE (default: the state
  // directory's identity file, made on the first run); --guest plays without one.
  std::string identity_file;
  bool guest = false;
  std::optional<protocol::Identity> identity;  // read (or made) by main before connecting
  // --forget-me: erase this identity's profile on the server (PROTOCOL.md 4.7c), after
  // the player typed yes (or --yes), and exit; the identity file is kept.
  bool forget_me = false;
  bool yes = false;
};

// Whether the field is drawn in braille dots for --glyphs and the environment.
bool fine_field(const Options& o);

// fts-client's exit status after --idle-exit-s ran out (0 quit, 1 error, 2 bad option).
inline constexpr int kIdleExitCode = 3;
// Whether idle_ms without a key is past --idle-exit-s, and what the client then says.
bool idle_over(const Options& o, std::uint64_t idle_ms);
std::string idle_text(const Options& o);

// The connection the options ask for: name, encoding, room choice, and `saved_token`
// (this server's last session, from the session store) to take our player back.
protocol::ClientConfig connection_config(const Options& o, std::optional<std::string> saved_token);

// Parses argv into o. Returns -1 to go on, else the exit code (0 after --help or
// --help-markdown, 2 after a bad option, with the reason on stderr).
int parse_options(int argc, char** argv, Options& o);

// --help and --help-markdown (docs/flags/fts-client.md), from the table.
std::string usage_text();
std::string markdown_text();

}  // namespace fts::client
