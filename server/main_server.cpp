// fts-server: hosts rooms (each a match) over UDP; `fts-server --console SOCKET CMD`
// talks to a running server's console. Settings come from flags and FTS_* variables
// (see --help); every bad setting is reported before anything binds.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/game_host.hpp"
#include "app/log.hpp"
#include "app/match_settings.hpp"
#include "app/options.hpp"
#include "host/journal.hpp"
#include "host/record.hpp"
#include "host/text.hpp"
#include "net/console.hpp"
#include "net/udp_server.hpp"

namespace {

std::optional<std::string> getenv_opt(const std::string& name) {
  const char* v = std::getenv(name.c_str());
  if (!v) return std::nullopt;
  return std::string(v);
}

int fail(const std::string& message) {
  std::cerr << "fts-server: " << message << "\n";
  return 2;
}

// Only the first room (id 1) is journaled so far, in DIR/main (see GameHost::journal_to).
constexpr const char* kRoomCode = "main";

// --resume: the room rebuilt from its journal, or nothing (reported) to start afresh.
std::optional<fts::host::ResumedRoom> resume_room(const std::filesystem::path& dir) {
  using namespace fts;
  const auto t0 = std::chrono::steady_clock::now();
  auto r = host::read_journal(dir, &server::GameHost::wire_event_count);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (auto* err = std::get_if<std::string>(&r)) {
    server::log_record(spdlog::level::err, "resume_skipped", {{"room", kRoomCode}, {"reason", *err}});
    return std::nullopt;
  }
  auto& room = std::get<host::ResumedRoom>(r);
  for (const auto& why : room.skipped)
    server::log_record(spdlog::level::warn, "resume_segment_skipped", {{"room", kRoomCode}, {"reason", why}});
  if (!room.damage.empty())
    server::log_record(spdlog::level::warn, "resume_damage", {{"room", kRoomCode}, {"damage", room.damage}});
  server::log_record(spdlog::level::info, "resumed",
                     {{"room", kRoomCode}, {"tick", room.state.tick}, {"level", room.state.level},
                      {"segment", room.segment}, {"checkpoint_tick", room.checkpoint_tick},
                      {"ticks_replayed", room.ticks_replayed}, {"hashes_checked", room.hashes_checked},
                      {"sessions", room.sessions.size()}, {"event_seq", room.event_seq},
                      {"hash", host::hex16(sim::match_hash(room.state))}, {"ms", ms}});
  return std::move(room);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fts;
  const std::vector<std::string> args(argv + 1, argv + argc);
  // The console's front end: fts-server --console SOCKET CMD [ARGS...]
  if (!args.empty() && (args[0] == "--console" || args[0].rfind("--console=", 0) == 0)) {
    const bool inline_path = args[0] != "--console";
    if (!inline_path && args.size() < 2) return fail("--console: needs the socket path and a command");
    const std::string path = inline_path ? args[0].substr(10) : args[1];
    return server::run_console_client(path, {args.begin() + (inline_path ? 1 : 2), args.end()});
  }
  auto parsed = server::parse_options(args, getenv_opt);
  if (auto* err = std::get_if<server::OptionError>(&parsed)) return fail(err->message);
  auto options = std::get<server::Options>(parsed);
  if (options.help) {
    std::cout << server::usage_text();
    return 0;
  }
  if (options.version) {
    std::cout << "fts-server " << FTS_VERSION << "\n";
    return 0;
  }

  if (!options.replay_path.empty()) {
    std::ifstream in(options.replay_path);
    if (!in) return fail("--replay: cannot read " + options.replay_path);
    auto r = host::replay_record(in);
    if (auto* err = std::get_if<std::string>(&r)) {
      std::cerr << "fts-server: replay of " << options.replay_path << " FAILED: " << *err << "\n";
      return 1;
    }
    const auto& rep = std::get<host::ReplayReport>(r);
    std::cout << R"({"replay":")" << options.replay_path << R"(","ticks":)" << rep.ticks << R"(,"hashes_checked":)"
              << rep.hashes_checked << R"(,"state_hash":")" << host::hex16(rep.final_hash) << "\"}\n";
    return 0;
  }

  // Defaults < --config file < FTS_* variables < flags.
  auto resolved = server::resolve_match_config(options);
  if (auto* err = std::get_if<std::string>(&resolved)) return fail(*err);
  auto config = std::get<sim::MatchConfig>(resolved);

  std::ofstream record;
  if (!options.record_path.empty()) {
    record.open(options.record_path);
    if (!record) return fail("--record: cannot write " + options.record_path);
  }

  if (!options.record_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.record_dir, ec);
    if (ec || !std::filesystem::is_directory(options.record_dir))
      return fail("--record-dir: cannot make directory " + options.record_dir + (ec ? ": " + ec.message() : ""));
  }

  server::init_logging(options.log_level, options.log_format);
  const std::filesystem::path room_dir = std::filesystem::path(options.journal_dir) / kRoomCode;
  std::optional<host::ResumedRoom> resumed;
  if (options.resume) resumed = resume_room(room_dir);
  if (resumed) {  // the journal's match goes on: its seed and config win over the flags
    config = resumed->config;
    options.seed = resumed->seed;
  }
  server::GameHost host(options, config, protocol::random_key());
  if (!options.record_dir.empty()) host.record_dir(options.record_dir, FTS_VERSION);
  if (resumed) host.resume_from(*resumed, 0);
  if (record.is_open()) host.record_to(record, FTS_VERSION);
  if (!options.journal_dir.empty()) {
    host::JournalConfig jc;
    jc.dir = room_dir;
    jc.room = kRoomCode;
    jc.version = FTS_VERSION;
    jc.seed = options.seed;
    jc.sync_ms = options.journal_sync_ms;
    jc.checkpoint_every_ticks = static_cast<std::int64_t>(options.journal_checkpoint_s * config.tick_rate_hz);
    host.journal_to(jc);
    const auto* journal = host.journal();
    if (!journal) return fail("--journal-dir: the first room could not be opened");
    if (const auto err = journal->stats().error; !err.empty()) return fail(err);
  }
  const int rc = server::run_udp_server(options, host, record.is_open() ? &record : nullptr);
  if (const auto* j = host.journal()) {
    const auto st = j->stats();
    server::log_record(st.error.empty() ? spdlog::level::info : spdlog::level::err, "journal",
                       {{"room", kRoomCode}, {"records", st.records}, {"bytes", st.bytes}, {"syncs", st.syncs},
                        {"segments", st.segments}, {"removed_segments", st.removed_segments},
                        {"dropped", st.dropped}, {"durable_tick", st.durable_tick}, {"error", st.error}});
  }
  return rc;
}
