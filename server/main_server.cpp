// fts-server: hosts rooms (each a match) over UDP; `fts-server --console SOCKET CMD`
// talks to a running server's console. Settings come from flags and FTS_* variables
// (see --help); every bad setting is reported before anything binds.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/game_host.hpp"
#include "app/log.hpp"
#include "app/match_settings.hpp"
#include "app/options.hpp"
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
  const auto& config = std::get<sim::MatchConfig>(resolved);

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
  server::GameHost host(options, config, protocol::random_key());
  if (record.is_open()) host.record_to(record, FTS_VERSION);
  if (!options.record_dir.empty()) host.record_dir(options.record_dir, FTS_VERSION);
  return server::run_udp_server(options, host, record.is_open() ? &record : nullptr);
}
