// fts-server's option table: one row per setting of Options (app/options.hpp), whose
// member initialisers are the defaults. --help, FTS_* variables, the --config file's
// overrides (app/match_settings.cpp) and docs/flags/fts-server.md come from it; a member
// of Options without a row does not build (the static_assert below).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <tuple>

#include "app/options.hpp"
#include "fts/cli/option_table.hpp"

namespace fts::server {

// The checks that are more than a range or a list of names (app/options.cpp).
bool parse_ip(const std::string& text, std::string& out);
bool parse_metrics(const std::string& text, std::string& out);
bool parse_peer(const std::string& text, std::string& out);
bool parse_agones(const std::string& text, std::uint16_t& out);
std::string show_text(const std::string& v);
std::string show_agones(const std::uint16_t& v);

inline constexpr std::string_view kAgonesWant = "must be on, off or the SDK's HTTP port 1..65535";

namespace option_table_detail {
using cli::Int, cli::OneOf, cli::Real, cli::Text, cli::Custom;
using O = Options;
using u32 = std::uint32_t;
constexpr Custom<std::string> kIp{parse_ip, show_text, "an IPv4 or IPv6 address"};
constexpr Custom<std::string> kMetrics{parse_metrics, show_text, "ADDR:PORT (an IP address, a port 1..65535), \"\": off"};
constexpr Custom<std::string> kPeer{parse_peer, show_text, "HOST:PORT (a name or an IP address, a port 1..65535), \"\": off"};
constexpr Custom<std::uint16_t> kAgones{parse_agones, show_agones, "on, off, 1..65535"};

inline constexpr auto kOptionTable = std::tuple{
    cli::value("--port", "FTS_PORT", &O::port, Int<std::uint16_t>{0, 65535}, "must be a port number 0..65535",
               "UDP port to listen on (0: any free port)", "PORT"),
    cli::value("--bind", "FTS_BIND", &O::bind, kIp, "must be an IPv4 or IPv6 address", "address to bind", "ADDR"),
    cli::overrides(cli::value("--tick-rate", "FTS_TICK_RATE", &O::tick_rate_hz, Int<u32>{10, 1000}, "must be 10..1000 Hz",
                              "simulation ticks per second (Hz)", "HZ"),
                   "tick_rate_hz", "fts-server runs 10..1000 whole ticks per second"),
    cli::value("--snapshot-rate", "FTS_SNAPSHOT_RATE", &O::snapshot_rate_hz, Int<u32>{1, 1000}, "must be 1..1000 Hz",
               "snapshots per second to each client (Hz)", "HZ"),
    cli::overrides(cli::value("--max-players", "FTS_MAX_PLAYERS", &O::max_players, Int<u32>{1, 64}, "must be 1..64",
                              "players in one room's match at once", "N"),
                   "max_players", "fts-server seats 1..64 players in a match"),
    cli::overrides(cli::value("--model", "FTS_MODEL", &O::model, OneOf{{"seed", "discrete", "continuous"}},
                              "must be seed, discrete or continuous", "physics model: seed, discrete or continuous", "MODEL"),
                   "model", "must be seed, discrete or continuous"),
    cli::value("--seed", "FTS_SEED", &O::seed, Int<std::uint64_t>{0, std::numeric_limits<std::uint64_t>::max()},
               "must be a non-negative integer", "seed of the match's random generator", "N"),
    cli::value("--config", "FTS_CONFIG", &O::config_path, Text{},
               "must be a file", "match configuration JSON (docker/server-config.example.json); a flag or variable "
               "of --tick-rate, --max-players or --model wins over its key", "FILE"),
    cli::value("--record", "FTS_RECORD", &O::record_path, Text{}, "must be a directory",
               "record the first room (id 1) into this directory, a journal keeping every segment (with --record-dir: room 1's)",
               "DIR"),
    cli::value("--replay", "FTS_REPLAY", &O::replay_path, Text{}, "must be a record",
               "re-run a record (a journal directory, or a record file of format 1), check every hash, exit", "PATH"),
    cli::value("--log-level", "FTS_LOG_LEVEL", &O::log_level, OneOf{{"trace", "debug", "info", "warn", "error", "off"}},
               "must be trace, debug, info, warn, error or off", "trace, debug, info, warn, error or off", "LEVEL"),
    cli::value("--log-format", "FTS_LOG_FORMAT", &O::log_format, OneOf{{"text", "json"}}, "must be text or json",
               "text, or json (one JSON record per line)", "FORMAT"),
    cli::value("--timeout-ms", "FTS_TIMEOUT_MS", &O::timeout_ms, Int<u32>{100, 3600000}, "must be 100..3600000 ms",
               "silence after which a client is dropped (ms)", "MS"),
    cli::value("--reconnect-window-ms", "FTS_RECONNECT_WINDOW_MS", &O::reconnect_window_ms, Int<u32>{0, 3600000},
               "must be 0..3600000 ms",
               "how long a dropped player's slot is kept (ms); while its room's match runs, the player (lives, coins) "
               "is kept until the match ends, its seat freed at the window's end",
               "MS"),
    cli::value("--input-expiry-ms", "FTS_INPUT_EXPIRY_MS", &O::input_expiry_ms, Int<u32>{10, 10000},
               "must be 10..10000 ms", "a held input goes neutral after this long without a new frame (ms)", "MS"),
    cli::value("--max-per-address", "FTS_MAX_PER_ADDRESS", &O::max_per_address, Int<u32>{1, 1024}, "must be 1..1024",
               "players at once from one IP address", "N"),
    cli::value("--idle-timeout-ms", "FTS_IDLE_TIMEOUT_MS", &O::idle_timeout_ms, Int<u32>{0, 3600000},
               "must be 0..3600000 ms",
               "a player without input this long in a round is dropped (ms, 0: never); its seat is freed, its lives "
               "and coins kept until the match ends (PROTOCOL.md 5.4), and fts-client stays and brings it back on a "
               "key; a player out of lives (watching) is never dropped",
               "MS"),
    cli::value("--stats-interval-ms", "FTS_STATS_INTERVAL_MS", &O::stats_interval_ms, Int<u32>{100, 3600000},
               "must be 100..3600000 ms", "period of the stats log line (ms)", "MS"),
    cli::value("--time-scale", "FTS_TIME_SCALE", &O::time_scale, Real{0.1, 100}, "must be 0.1..100",
               "run ticks this many times faster than real time (tests)", "X"),
    cli::value("--journal-dir", "FTS_JOURNAL_DIR", &O::journal_dir, Text{true}, "must be a directory",
               "keep each room's crash-safe journal under this directory", "DIR"),
    cli::value("--journal-sync-ms", "FTS_JOURNAL_SYNC_MS", &O::journal_sync_ms, Int<u32>{1, 10000}, "must be 1..10000 ms",
               "make the journal durable (fdatasync) at most this often (ms)", "MS"),
    cli::value("--journal-checkpoint-s", "FTS_JOURNAL_CHECKPOINT_S", &O::journal_checkpoint_s, Int<u32>{1, 3600},
               "must be 1..3600 s", "write a journal checkpoint (new segment) this often (s)", "S"),
    cli::on("--resume", "FTS_RESUME", &O::resume, "rebuild every room of --journal-dir, then open the port"),
    cli::value("--profiles", "FTS_PROFILES", &O::profiles, Text{}, "must be a SQLite file, a postgresql:// URL or off",
               "players' profiles and leaderboards: a SQLite file (default: "
               "$XDG_STATE_HOME/fear-the-sphere/server/profiles.sqlite), a postgresql://USER@HOST/DB URL (a fleet "
               "shares one), or off",
               "FILE|URL|off"),
    cli::value("--agones", "FTS_AGONES", &O::agones_port, kAgones, kAgonesWant,
               "Agones SDK sidecar: on, off or its REST port (on, at its port, when AGONES_SDK_HTTP_PORT is set)",
               "on|off|PORT"),
    cli::value("--agones-health-ms", "FTS_AGONES_HEALTH_MS", &O::agones_health_ms, Int<u32>{100, 60000},
               "must be 100..60000 ms", "period of the Agones health ping, sent from the tick loop (ms)", "MS"),
    cli::value("--drain-grace-ms", "FTS_DRAIN_GRACE_MS", &O::drain_grace_ms, Int<u32>{0, 3600000},
               "must be 0..3600000 ms", "with Agones, SIGTERM drains: the longest wait for the last match (ms)", "MS"),
    cli::value("--metrics", "FTS_METRICS", &O::metrics_address, kMetrics,
               "must be ADDR:PORT with an IPv4 address and a port 1..65535 (\"\": off)",
               "serve Prometheus /metrics on ADDR:PORT (off when empty; never the game port)", "ADDR:PORT"),
    cli::value("--max-rooms", "FTS_MAX_ROOMS", &O::max_rooms, Int<u32>{1, 1024}, "must be 1..1024",
               "rooms at once, each a match of --max-players", "N"),
    cli::value("--max-rooms-per-host", "FTS_MAX_ROOMS_PER_HOST", &O::max_rooms_per_host, Int<u32>{1, 1024},
               "must be 1..1024",
               "open rooms one IP address may have made; at the bound its own empty room makes way, else address_full",
               "N"),
    cli::value("--threads", "FTS_THREADS", &O::threads, Int<u32>{0, 256}, "must be 0..256 (0: every core)",
               "threads that step the rooms; 0: every core the process may use", "N"),
    cli::value("--room-idle-ms", "FTS_ROOM_IDLE_MS", &O::room_idle_ms, Int<u32>{0, 86400000}, "must be 0..86400000 ms",
               "a room with nobody connected this long is closed (ms)", "MS"),
    cli::value("--max-spectators", "FTS_MAX_SPECTATORS", &O::max_spectators, Int<u32>{0, 64}, "must be 0..64",
               "spectators per room", "N"),
    cli::value("--record-dir", "FTS_RECORD_DIR", &O::record_dir, Text{}, "must be a directory",
               "record each room into DIR/room-<id>/, a journal keeping every segment (with --record: the rooms but 1)", "DIR"),
    cli::value("--console-socket", "FTS_CONSOLE_SOCKET", &O::console_path, Text{}, "must be a path",
               "serve the host's console on this UNIX socket (mode 0600)", "PATH"),
    cli::value("--handover-listen", "FTS_HANDOVER_LISTEN", &O::handover_listen, kMetrics,
               "must be ADDR:PORT with an IP address and a port 1..65535 (\"\": off)",
               "take rooms handed over by peer servers on this TCP ADDR:PORT (needs --fleet-secret, --journal-dir)",
               "ADDR:PORT"),
    cli::value("--fleet-secret", "FTS_FLEET_SECRET", &O::fleet_secret_path, Text{}, "must be a file",
               "the fleet's shared secret, a file of at least 32 bytes: authenticates room hand-overs both ways",
               "FILE"),
    cli::value("--handover-to", "FTS_HANDOVER_TO", &O::handover_to, kPeer,
               "must be HOST:PORT with a port 1..65535 (\"\": off)",
               "a drain (the console's, or SIGTERM under Agones) first hands every room to this peer's "
               "--handover-listen (a name may be a Service of the fleet's peers; needs --fleet-secret)",
               "HOST:PORT"),
    cli::on("--version", "", &O::version, "print the version"),
    // The fleet's Counters and Lists for the given limits, for the test that holds
    // docker/agones/ to them (server/fleet/fleet_names.hpp).
    cli::hidden(cli::on("--print-fleet-names", "", &O::print_fleet_names, "print the fleet's Counters and Lists")),
};
}  // namespace option_table_detail

using option_table_detail::kOptionTable;

// That every member of Options has a row is checked once, in options.cpp.

}  // namespace fts::server
