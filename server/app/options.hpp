// fts-server's settings from flags and the environment (FTS_PORT, ...). Flags win over
// the environment; every bad value is an error naming the flag (or variable) and value,
// found before anything binds a port. A setting's default is its initialiser here and
// nowhere else; its flag, variable, check and help are its row in app/option_table.hpp.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "fts/cli/option_table.hpp"

namespace fts::server {

struct Options {
  std::uint16_t port = 7777;
  std::string bind = "0.0.0.0";
  std::uint32_t tick_rate_hz = 100;
  std::uint32_t snapshot_rate_hz = 20;
  std::uint32_t max_players = 8;
  std::string model = "continuous";
  std::uint64_t seed = 1;
  std::string config_path;   // "" : built-in defaults
  std::string record_path;   // "" : no recording of room 1 but --record-dir's
  std::string replay_path;   // non-empty: re-run a recording and check its hashes, no network
  std::string log_level = "info";   // trace debug info warn error off
  std::string log_format = "text";  // text | json
  std::uint32_t timeout_ms = 10000;
  std::uint32_t reconnect_window_ms = 60000;
  std::uint32_t input_expiry_ms = 150;  // a held input goes neutral without a new frame
  std::uint32_t max_per_address = 4;      // seated players from one host (address without port)
  std::uint32_t idle_timeout_ms = 120000;  // no real input this long while playing: dropped (0: never)
  std::uint32_t stats_interval_ms = 10000;
  double time_scale = 1.0;  // ticks run this many times faster than real time (tests)
  // Crash-safe rooms (server/store/journal.hpp): "" : no journal.
  std::string journal_dir;
  std::uint32_t journal_sync_ms = 100;       // fdatasync at most this often
  std::uint32_t journal_checkpoint_s = 5;    // a checkpoint (new segment) this often (bounds a resume's replay)
  bool resume = false;                       // rebuild the rooms of --journal-dir first
  // Players' profiles (issue 41): "" the default SQLite file under the state directory
  // ($XDG_STATE_HOME/fear-the-sphere/server/profiles.sqlite), a SQLite path, a
  // postgresql:// URL (a fleet shares one), or "off".
  std::string profiles;
  // Fleet (server/fleet/): the Agones SDK sidecar's REST port (0: Agones off; --agones
  // on, or AGONES_SDK_HTTP_PORT set, turns it on), the health ping period, how long a
  // drain waits for the last match, and the Prometheus endpoint ("": off).
  std::uint16_t agones_port = 0;
  std::uint32_t agones_health_ms = 2000;
  std::uint32_t drain_grace_ms = 25000;
  std::string metrics_address;  // "ADDR:PORT"
  std::uint32_t max_rooms = 64;         // rooms at once; each a match of max_players
  // Open rooms one host (address without port) may have made: one host made every room
  // (a create then a bye, 5 a second) and the rest of the world got server_full (issue 36).
  // A host at the bound gets its own empty rooms back first, else address_full.
  std::uint32_t max_rooms_per_host = 4;
  std::uint32_t threads = 0;            // threads stepping the rooms (0: every usable core)
  std::uint32_t room_idle_ms = 60000;   // a room without a connected client this long is closed
  std::uint32_t max_spectators = 8;     // spectators per room (0: none)
  std::string record_dir;   // "" : no per-room records; else DIR/room-<id>/ per room (room 1: record_path if set)
  std::string console_path;  // "" : no console; else the host's UNIX socket (mode 0600)
  // Rooms that move (issue 42, server/net/handover.hpp): take rooms handed over by peers
  // on this TCP ADDR:PORT ("": off); the fleet's shared secret (a file) authenticates
  // both ends, and is needed to hand a room over too.
  std::string handover_listen;
  std::string fleet_secret_path;
  std::string handover_to;  // HOST:PORT: a drain hands every room to this peer first
  bool help = false;      // --help (the table's library adds it)
  bool markdown = false;  // --help-markdown: the flag reference (docs/flags/fts-server.md)
  bool version = false;
  bool print_fleet_names = false;  // print the fleet's Counters and Lists (JSON lines), exit
  // The settings given by a flag or an FTS_* variable, by flag name without dashes
  // ("tick-rate"); only these override the --config file (see resolve_match_config).
  std::set<std::string> given;
};

struct OptionError {
  std::string message;
};

using EnvLookup = std::function<std::optional<std::string>(const std::string&)>;

// Parses argv-style arguments (without the program name) over the environment, by the
// table in app/option_table.hpp.
std::variant<Options, OptionError> parse_options(const std::vector<std::string>& args, const EnvLookup& env);

// --help, and --help-markdown (docs/flags/fts-server.md), from the table.
std::string usage_text();
std::string markdown_text();

// The table's rows without their types (flag, env, default_value, help, ...): for the
// documentation's tests.
const std::vector<cli::RowInfo>& option_docs();

}  // namespace fts::server
