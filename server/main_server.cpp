// fts-server: hosts rooms (each a match) over UDP; `fts-server --console SOCKET CMD`
// talks to a running server's console. Settings come from flags and FTS_* variables
// (see --help); every bad setting is reported before anything binds.
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "app/game_host.hpp"
#include "app/log.hpp"
#include "app/match_settings.hpp"
#include "app/options.hpp"
#include "app/profile_setup.hpp"
#include "app/room_journals.hpp"
#include "fleet/fleet_names.hpp"
#include "store/journal.hpp"
#include "fts/room/record.hpp"
#include "fts/room/text.hpp"
#include "net/console.hpp"
#include "net/udp_server.hpp"

namespace {

std::optional<std::string> getenv_opt(const std::string& name) {
  const char* v = std::getenv(name.c_str());
  if (!v) return std::nullopt;
  return std::string(v);
}

// User + system CPU time of the process so far, all threads (ms).
double process_cpu_ms() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  auto ms = [](const timeval& t) { return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_usec) / 1e3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

int fail(const std::string& message) {
  std::cerr << "fts-server: " << message << "\n";
  return 2;
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
  if (options.markdown) {
    std::cout << server::markdown_text();
    return 0;
  }
  if (options.version) {
    std::cout << "fts-server " << FTS_VERSION << "\n";
    return 0;
  }
  if (options.print_fleet_names) {
    std::cout << server::fleet_names_json_lines(options.max_rooms, options.max_players);
    return 0;
  }

  if (!options.replay_path.empty()) {
    auto r = room::replay_history(options.replay_path);
    if (auto* err = std::get_if<std::string>(&r)) {
      std::cerr << "fts-server: replay of " << options.replay_path << " FAILED: " << *err << "\n";
      return 1;
    }
    const auto& rep = std::get<room::ReplayReport>(r);
    std::cout << R"({"replay":")" << options.replay_path << R"(","format":")" << rep.format << R"(","ticks":)" << rep.ticks << R"(,"hashes_checked":)"
              << rep.hashes_checked << R"(,"state_hash":")" << room::hex16(rep.final_hash) << "\"}\n";
    return 0;
  }

  // Defaults < --config file < FTS_* variables < flags.
  auto resolved = server::resolve_match_config(options);
  if (auto* err = std::get_if<std::string>(&resolved)) return fail(*err);
  auto config = std::get<sim::MatchConfig>(resolved);

  // A record is a directory (a journal that keeps every segment): made now, so that a
  // path that cannot be one is said at start.
  for (const auto& [flag, dir] : {std::pair{"--record", options.record_path}, std::pair{"--record-dir", options.record_dir}}) {
    if (dir.empty()) continue;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
      return fail(std::string(flag) + ": cannot make directory " + dir + (ec ? ": " + ec.message() : ""));
  }

  server::init_logging(options.log_level, options.log_format);
  // --journal-dir: the directory locked; --resume: every room's journal read (rooms in
  // parallel), before anything binds. Without --resume, journals left there are an error:
  // starting afresh over them would lose what the players earned.
  std::unique_ptr<server::JournalRoot> journal_root;
  std::vector<server::RoomJournalRead> reads;
  const auto resume_t0 = std::chrono::steady_clock::now();
  const double resume_cpu0 = process_cpu_ms();
  if (!options.journal_dir.empty()) {
    journal_root = std::make_unique<server::JournalRoot>(options.journal_dir);
    if (!journal_root->error().empty()) return fail(journal_root->error());
    const auto codes = journal_root->room_codes();
    if (!options.resume && !codes.empty())
      return fail("--journal-dir: " + options.journal_dir + " holds the journals of " + std::to_string(codes.size()) +
                  " rooms (" + codes.front() + (codes.size() > 1 ? ", ..." : "") +
                  "): start with --resume to bring them back, or remove them");
    if (options.resume) reads = server::read_room_journals(options.journal_dir, codes, std::thread::hardware_concurrency());
  }
  // Profiles (issue 41): a SQLite file that is not ours (corrupt, foreign, newer) is
  // refused now, with what is wrong; a PostgreSQL that does not answer yet is only said:
  // the writer keeps trying, and spools meanwhile.
  std::unique_ptr<profiles::Writer> profile_writer;
  const auto place = server::profile_place(options.profiles, std::getenv("XDG_STATE_HOME"), std::getenv("HOME"));
  if (!place.error.empty()) return fail(place.error);
  if (!place.off) {
    // This first connection is closed before the writer opens its own: one at a time.
    if (auto first = profiles::Store::open(place.url); auto* why = std::get_if<std::string>(&first)) {
      if (!profiles::is_postgresql_url(place.url)) return fail("--profiles: " + *why);
      server::log_record(spdlog::level::warn, "profiles_unreachable", {{"error", *why}});
    }
    profiles::WriterConfig wc;
    wc.url = place.url;
    wc.spool_dir = place.spool_dir;
    profile_writer = std::make_unique<profiles::Writer>(wc);
    if (!profile_writer->spool_error().empty()) return fail("--profiles: " + profile_writer->spool_error());
    server::log_record(spdlog::level::info, "profiles",
                       {{"where", profile_writer->stats().where}, {"spool", place.spool_dir},
                        {"adopted", profile_writer->stats().adopted}});
  }
  // The journals' matches go on: their config wins over the flags.
  if (auto resumed_cfg = server::resumed_config(reads)) config = *resumed_cfg;
  server::GameHost host(options, config, protocol::random_key());
  if (profile_writer) {
    // The wall clock of profiles; FTS_TEST_CLOCK_OFFSET_S moves it (tests: "a day later").
    const char* offset_env = std::getenv("FTS_TEST_CLOCK_OFFSET_S");
    const std::int64_t offset = offset_env ? std::strtoll(offset_env, nullptr, 10) : 0;
    host.use_profiles(profile_writer.get(), [offset] {
      return static_cast<std::int64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                           std::chrono::system_clock::now().time_since_epoch())
                                           .count()) +
             offset;
    });
  }
  if (!options.record_dir.empty()) host.record_dir(options.record_dir, FTS_VERSION);
  if (!options.record_path.empty()) host.record_to(options.record_path, FTS_VERSION);
  if (journal_root) {
    store::JournalConfig jc;
    jc.dir = options.journal_dir;
    jc.version = FTS_VERSION;
    jc.sync_ms = options.journal_sync_ms;
    jc.checkpoint_every_ticks = static_cast<std::int64_t>(options.journal_checkpoint_s * config.tick_rate_hz);
    host.journal_rooms(jc);
  }
  if (options.resume) {
    const auto sum = server::resume_rooms(host, reads, config, 0);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - resume_t0).count();
    server::log_record(spdlog::level::info, "resume_done",
                       {{"rooms", sum.rooms}, {"resumed", sum.resumed}, {"skipped", sum.skipped},
                        {"sessions", sum.sessions}, {"threads", std::thread::hardware_concurrency()}, {"ms", ms},
                        {"cpu_ms", process_cpu_ms() - resume_cpu0}});
  }
  const int rc = server::run_udp_server(options, host);
  return rc;
}
