#include "app/options.hpp"

#include <charconv>
#include <cstdlib>
#include <limits>

#include <CLI/CLI.hpp>

#include "fts/io/address.hpp"

namespace fts::server {
namespace {

constexpr std::uint16_t kAgonesDefaultPort = 9358;  // the SDK server's REST default

template <class T>
bool parse_uint(const std::string& s, T& out, T lo, T hi) {
  std::uint64_t v = 0;
  const auto* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc() || p != end || s.empty()) return false;
  if (v < lo || v > hi) return false;
  out = static_cast<T>(v);
  return true;
}

bool one_of(const std::string& v, std::initializer_list<const char*> allowed) {
  for (const char* a : allowed)
    if (v == a) return true;
  return false;
}

// Applies one setting; `source` names it in errors ("--port" or "FTS_PORT").
std::optional<OptionError> apply(Options& o, const std::string& key, const std::string& value,
                                 const std::string& source) {
  auto bad = [&](const std::string& want) {
    return OptionError{source + ": " + want + ", got \"" + value + "\""};
  };
  if (key == "port") {
    if (!parse_uint<std::uint16_t>(value, o.port, 0, 65535)) return bad("must be a port number 0..65535");
  } else if (key == "bind") {
    // Checked here (not at bind time) so a typo is a usage error before anything starts.
    if (!io::is_ip_address(value)) return bad("must be an IPv4 or IPv6 address");
    o.bind = value;
  } else if (key == "tick-rate") {
    if (!parse_uint<std::uint32_t>(value, o.tick_rate_hz, 10, 1000)) return bad("must be 10..1000 Hz");
  } else if (key == "snapshot-rate") {
    if (!parse_uint<std::uint32_t>(value, o.snapshot_rate_hz, 1, 1000)) return bad("must be 1..1000 Hz");
  } else if (key == "max-players") {
    if (!parse_uint<std::uint32_t>(value, o.max_players, 1, 64)) return bad("must be 1..64");
  } else if (key == "model") {
    if (!one_of(value, {"seed", "discrete", "continuous"})) return bad("must be seed, discrete or continuous");
    o.model = value;
  } else if (key == "seed") {
    if (!parse_uint<std::uint64_t>(value, o.seed, 0, std::numeric_limits<std::uint64_t>::max()))
      return bad("must be a non-negative integer");
  } else if (key == "config") {
    o.config_path = value;
  } else if (key == "record") {
    o.record_path = value;
  } else if (key == "replay") {
    o.replay_path = value;
  } else if (key == "log-level") {
    if (!one_of(value, {"trace", "debug", "info", "warn", "error", "off"}))
      return bad("must be trace, debug, info, warn, error or off");
    o.log_level = value;
  } else if (key == "log-format") {
    if (!one_of(value, {"text", "json"})) return bad("must be text or json");
    o.log_format = value;
  } else if (key == "timeout-ms") {
    if (!parse_uint<std::uint32_t>(value, o.timeout_ms, 100, 3600000)) return bad("must be 100..3600000 ms");
  } else if (key == "reconnect-window-ms") {
    if (!parse_uint<std::uint32_t>(value, o.reconnect_window_ms, 0, 3600000)) return bad("must be 0..3600000 ms");
  } else if (key == "input-expiry-ms") {
    if (!parse_uint<std::uint32_t>(value, o.input_expiry_ms, 10, 10000)) return bad("must be 10..10000 ms");
  } else if (key == "max-per-address") {
    if (!parse_uint<std::uint32_t>(value, o.max_per_address, 1, 1024)) return bad("must be 1..1024");
  } else if (key == "idle-timeout-ms") {
    if (!parse_uint<std::uint32_t>(value, o.idle_timeout_ms, 0, 3600000)) return bad("must be 0..3600000 ms");
  } else if (key == "stats-interval-ms") {
    if (!parse_uint<std::uint32_t>(value, o.stats_interval_ms, 100, 3600000)) return bad("must be 100..3600000 ms");
  } else if (key == "journal-dir") {
    if (value.empty()) return bad("must be a directory");
    o.journal_dir = value;
  } else if (key == "journal-sync-ms") {
    if (!parse_uint<std::uint32_t>(value, o.journal_sync_ms, 1, 10000)) return bad("must be 1..10000 ms");
  } else if (key == "journal-checkpoint-s") {
    if (!parse_uint<std::uint32_t>(value, o.journal_checkpoint_s, 1, 3600)) return bad("must be 1..3600 s");
  } else if (key == "max-rooms") {
    if (!parse_uint<std::uint32_t>(value, o.max_rooms, 1, 1024)) return bad("must be 1..1024");
  } else if (key == "max-rooms-per-host") {
    if (!parse_uint<std::uint32_t>(value, o.max_rooms_per_host, 1, 1024)) return bad("must be 1..1024");
  } else if (key == "threads") {
    if (!parse_uint<std::uint32_t>(value, o.threads, 0, 256)) return bad("must be 0..256 (0: every core)");
  } else if (key == "room-idle-ms") {
    if (!parse_uint<std::uint32_t>(value, o.room_idle_ms, 0, 86400000)) return bad("must be 0..86400000 ms");
  } else if (key == "max-spectators") {
    if (!parse_uint<std::uint32_t>(value, o.max_spectators, 0, 64)) return bad("must be 0..64");
  } else if (key == "record-dir") {
    o.record_dir = value;
  } else if (key == "console-socket") {
    o.console_path = value;
  } else if (key == "time-scale") {
    char* end = nullptr;
    o.time_scale = std::strtod(value.c_str(), &end);
    if (value.empty() || *end || !(o.time_scale >= 0.1 && o.time_scale <= 100.0)) return bad("must be 0.1..100");
  } else if (key == "agones") {
    // "on": the sidecar's documented default port, unless AGONES_SDK_HTTP_PORT names one.
    if (value == "off") {
      o.agones_port = 0;
    } else if (value == "on") {
      if (o.agones_port == 0) o.agones_port = kAgonesDefaultPort;
    } else if (!parse_uint<std::uint16_t>(value, o.agones_port, 1, 65535)) {
      return bad("must be on, off or the SDK's HTTP port 1..65535");
    }
  } else if (key == "agones-health-ms") {
    if (!parse_uint<std::uint32_t>(value, o.agones_health_ms, 100, 60000)) return bad("must be 100..60000 ms");
  } else if (key == "drain-grace-ms") {
    if (!parse_uint<std::uint32_t>(value, o.drain_grace_ms, 0, 3600000)) return bad("must be 0..3600000 ms");
  } else if (key == "metrics") {
    // Checked here so a typo is a usage error; never the game port (checked after parsing).
    const auto colon = value.rfind(':');
    std::uint16_t port = 0;
    if (value.empty()) {
      o.metrics_address.clear();
    } else if (colon == std::string::npos || !io::is_ip_address(value.substr(0, colon)) ||
        !parse_uint<std::uint16_t>(value.substr(colon + 1), port, 1, 65535))
      return bad("must be ADDR:PORT with an IPv4 address and a port 1..65535 (\"\": off)");
    else
      o.metrics_address = value;
  } else {
    return OptionError{"unknown setting " + source};
  }
  o.given.insert(key);
  return std::nullopt;
}

std::string env_name(const std::string& key) {
  std::string name = "FTS_";
  for (char c : key) name += c == '-' ? '_' : static_cast<char>(c >= 'a' && c <= 'z' ? c - 32 : c);
  return name;
}

}  // namespace

const std::vector<OptionDoc>& option_docs() {
  static const std::vector<OptionDoc> docs = {
      {"--port", "FTS_PORT", "7777", "UDP port to listen on (0: any free port)"},
      {"--bind", "FTS_BIND", "0.0.0.0", "address to bind"},
      {"--tick-rate", "FTS_TICK_RATE", "100", "simulation ticks per second (Hz)"},
      {"--snapshot-rate", "FTS_SNAPSHOT_RATE", "20", "snapshots per second to each client (Hz)"},
      {"--max-players", "FTS_MAX_PLAYERS", "8", "players in one room's match at once"},
      {"--model", "FTS_MODEL", "continuous", "physics model: seed, discrete or continuous"},
      {"--seed", "FTS_SEED", "1", "seed of the match's random generator"},
      {"--config", "FTS_CONFIG", "", "match configuration JSON (docker/server-config.example.json)"},
      {"--record", "FTS_RECORD", "", "record the first room (id 1) into this directory, a journal keeping every segment (not with --record-dir)"},
      {"--replay", "FTS_REPLAY", "", "re-run a record (a journal directory, or a record file of format 1), check every hash, exit"},
      {"--log-level", "FTS_LOG_LEVEL", "info", "trace, debug, info, warn, error or off"},
      {"--log-format", "FTS_LOG_FORMAT", "text", "text or json (one JSON record per line)"},
      {"--timeout-ms", "FTS_TIMEOUT_MS", "10000", "silence after which a client is dropped (ms)"},
      {"--reconnect-window-ms", "FTS_RECONNECT_WINDOW_MS", "60000", "how long a dropped player's slot is kept (ms)"},
      {"--input-expiry-ms", "FTS_INPUT_EXPIRY_MS", "150", "a held input goes neutral after this long without a new frame (ms)"},
      {"--max-per-address", "FTS_MAX_PER_ADDRESS", "4", "players at once from one IP address (1..1024)"},
      {"--idle-timeout-ms", "FTS_IDLE_TIMEOUT_MS", "120000", "a player without input this long in a round is dropped (ms, 0: never)"},
      {"--stats-interval-ms", "FTS_STATS_INTERVAL_MS", "10000", "period of the stats log line (ms)"},
      {"--time-scale", "FTS_TIME_SCALE", "1", "run ticks this many times faster than real time (tests)"},
      {"--journal-dir", "FTS_JOURNAL_DIR", "", "keep each room's crash-safe journal under this directory"},
      {"--journal-sync-ms", "FTS_JOURNAL_SYNC_MS", "100", "make the journal durable (fdatasync) at most this often (ms)"},
      {"--journal-checkpoint-s", "FTS_JOURNAL_CHECKPOINT_S", "5", "write a journal checkpoint (new segment) this often (s)"},
      {"--agones", "FTS_AGONES", "off", "Agones SDK sidecar: on, off or its REST port (on when AGONES_SDK_HTTP_PORT is set)"},
      {"--agones-health-ms", "FTS_AGONES_HEALTH_MS", "2000", "period of the Agones health ping, sent from the tick loop (ms)"},
      {"--drain-grace-ms", "FTS_DRAIN_GRACE_MS", "25000", "with Agones, SIGTERM drains: the longest wait for the last match (ms)"},
      {"--metrics", "FTS_METRICS", "", "serve Prometheus /metrics on ADDR:PORT (off when empty)"},
      {"--max-rooms", "FTS_MAX_ROOMS", "64", "rooms at once, each a match of --max-players (1..1024)"},
      {"--max-rooms-per-host", "FTS_MAX_ROOMS_PER_HOST", "4", "open rooms one IP address may have made (1..1024)"},
      {"--threads", "FTS_THREADS", "0", "threads that step the rooms; 0: every core the process may use (0..256)"},
      {"--room-idle-ms", "FTS_ROOM_IDLE_MS", "60000", "a room with nobody connected this long is closed (ms)"},
      {"--max-spectators", "FTS_MAX_SPECTATORS", "8", "spectators per room (0..64)"},
      {"--record-dir", "FTS_RECORD_DIR", "", "record each room into DIR/room-<id>/, a journal keeping every segment (not with --record)"},
      {"--console-socket", "FTS_CONSOLE_SOCKET", "", "serve the host's console on this UNIX socket (mode 0600)"},
  };
  return docs;
}

std::string usage_text() {
  std::string s = "usage: fts-server [options]\n\nOptions (each also settable from the environment):\n";
  for (const auto& d : option_docs()) {
    std::string left = "  " + d.flag + " V";
    left.resize(30, ' ');
    s += left + d.meaning + " [" + d.env + (d.default_value.empty() ? "" : ", default " + d.default_value) + "]\n";
  }
  s += "  --resume                    rebuild every room of --journal-dir, then open the port [FTS_RESUME=1]\n";
  s += "  --help                      this text\n  --version                   print the version\n";
  return s;
}

std::variant<Options, OptionError> parse_options(const std::vector<std::string>& args, const EnvLookup& env) {
  // CLI11 splits the command line (--flag V, --flag=V, the last of a repeated flag);
  // apply() checks each value, so a flag and its variable give the same message.
  CLI::App app{"", "fts-server"};
  app.set_help_flag();
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::vector<CLI::Option*> flags;
  for (const auto& d : option_docs()) flags.push_back(app.add_option(d.flag));
  auto* help = app.add_flag("-h,--help");
  auto* version = app.add_flag("--version");
  auto* resume = app.add_flag("--resume");
  // Hidden (not in --help): the fleet's Counters and Lists for the given limits, for the
  // test that holds docker/agones/ to them (server/fleet/fleet_names.hpp).
  auto* print_fleet_names = app.add_flag("--print-fleet-names");
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them reversed
  } catch (const CLI::ArgumentMismatch&) {
    // Only a value flag at the very end lacks its value (any next argument is taken).
    return OptionError{args.back().substr(0, args.back().find('=')) + ": needs a value"};
  } catch (const CLI::ParseError& e) {
    return OptionError{std::string(e.what()) + " (see --help)"};
  }
  if (!app.remaining().empty()) {
    const std::string a = app.remaining().front();
    if (a.rfind("--", 0) == 0) return OptionError{"unknown flag " + a.substr(0, a.find('=')) + " (see --help)"};
    return OptionError{"unexpected argument \"" + a + "\" (see --help)"};
  }

  Options o;
  o.help = help->count() > 0;
  o.version = version->count() > 0;
  o.print_fleet_names = print_fleet_names->count() > 0;
  if (auto v = env("FTS_RESUME")) o.resume = *v == "1";
  if (resume->count() > 0) o.resume = true;
  // Agones sets AGONES_SDK_HTTP_PORT for the game server: its presence turns the SDK on
  // (FTS_AGONES / --agones off still win, being applied after it).
  if (auto port = env("AGONES_SDK_HTTP_PORT")) {
    if (auto err = apply(o, "agones", *port, "AGONES_SDK_HTTP_PORT")) return *err;
    o.given.erase("agones");
  }
  for (std::size_t i = 0; i < flags.size(); ++i) {
    const std::string key = option_docs()[i].flag.substr(2);
    if (auto v = env(env_name(key))) {
      if (auto err = apply(o, key, *v, env_name(key))) return *err;
    }
  }
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (flags[i]->count() == 0) continue;
    const std::string& flag = option_docs()[i].flag;
    if (auto err = apply(o, flag.substr(2), flags[i]->results().back(), flag)) return *err;
  }
  if (o.resume && o.journal_dir.empty()) return OptionError{"--resume: needs --journal-dir DIR (where the journals are)"};
  // Refused rather than honoured: room 1 would need two recorders, and --record-dir
  // already records room 1 (DIR/room-1/). Checked before any directory is made.
  if (!o.record_path.empty() && !o.record_dir.empty())
    return OptionError{"--record PATH and --record-dir DIR (or FTS_RECORD and FTS_RECORD_DIR) cannot be used together: "
                       "--record-dir already records room 1 as DIR/room-1; give one of them"};
  if (!o.metrics_address.empty() &&
      o.metrics_address.substr(o.metrics_address.rfind(':') + 1) == std::to_string(o.port))
    return OptionError{"--metrics: must not be the game port " + std::to_string(o.port) + ", got \"" +
                       o.metrics_address + "\""};
  return o;
}

}  // namespace fts::server
