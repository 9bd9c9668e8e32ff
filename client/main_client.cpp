// fts-client: the program. Options, the replay mode, --forget-me (forget_me.cpp), the
// server's address, the name (--name-file) and the start screen in the plain terminal,
// then the game (game.cpp) in the raw one, and at the end the terminal given back and
// --stats-file written.
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <variant>

#include "client_options.hpp"
#include "forget_me.hpp"
#include "game.hpp"
#include "net/identity_store.hpp"
#include "net/link_stats.hpp"
#include "net/session_store.hpp"
#include "replay/replay_loop.hpp"
#include "term/terminal.hpp"
#include "ui/sanitize.hpp"
#include "ui/start_screen.hpp"

using namespace fts::client;

namespace {

// One line typed in the plain terminal, waiting at most idle_s (0: for ever). False at
// the end of input and when the time ran out (timed_out set).
bool read_line(std::string& line, int idle_s, bool& timed_out) {
  if (idle_s > 0 && std::cin.rdbuf()->in_avail() <= 0) {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    int n = 0;
    do {
      n = ::poll(&p, 1, idle_s * 1000);
    } while (n < 0 && errno == EINTR);
    if (n == 0) {
      timed_out = true;
      return false;
    }
  }
  return static_cast<bool>(std::getline(std::cin, line));
}

// The name kept in path (--name-file); asked for and saved when it holds none. "" when
// the person typed none (end of input, time-out).
std::string name_from_file(const std::string& path, int idle_s, bool& timed_out) {
  std::string line;
  if (std::ifstream in(path); in && std::getline(in, line) && !player_name(line).empty()) return player_name(line);
  for (int tries = 0; tries < 5; ++tries) {
    std::cout << "Your name (1 to 16 letters, digits or signs): " << std::flush;
    if (!read_line(line, idle_s, timed_out)) return "";
    const std::string name = player_name(line);
    if (name.empty()) continue;
    const mode_t old = ::umask(077);
    std::ofstream(path) << name << "\n";
    ::umask(old);
    return name;
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  Options opts;
  if (const int code = parse_options(argc, argv, opts); code >= 0) return code;
  if (!opts.replay.empty()) {
    std::string message;
    const int code = run_replay(opts.replay, opts.kitty, fine_field(opts), message);
    if (!message.empty()) std::cerr << "fts-client: " << message << "\n";
    return code;
  }
  fts::io::asio::io_context io;
  std::string why;
  const auto server = fts::io::resolve(io, opts.host, opts.port, why);
  if (!server) {
    std::cerr << "fts-client: cannot resolve " << opts.host << ":" << opts.port << ": " << why << "\n";
    return 1;
  }
  bool timed_out = false;
  const auto idle_end = [&] {
    std::cerr << "\nfts-client: " << idle_text(opts) << "\n";
    return kIdleExitCode;
  };
  // The identity: read, or made on the first run (PROTOCOL.md 5.8); --guest: none.
  std::string identity_path;
  if (!opts.guest) {
    const std::string path = !opts.identity_file.empty()
                                 ? opts.identity_file
                                 : default_identity_path(state_dir(std::getenv("XDG_STATE_HOME"), std::getenv("HOME")));
    identity_path = path;
    // --forget-me erases an identity's profile: one that does not exist has none.
    if (opts.forget_me && (path.empty() || !std::filesystem::exists(path))) {
      std::cerr << "fts-client: no identity" << (path.empty() ? std::string() : " at " + path)
                << ": nothing to forget (--identity FILE names another)\n";
      return 1;
    }
    if (!path.empty()) {
      opts.identity = load_or_create_identity(path, why);
      if (!opts.identity) {
        std::cerr << "fts-client: " << why << " (--guest plays without an identity)\n";
        return 1;
      }
    }
  }
  if (opts.forget_me) return forget_me(io, opts, *server, identity_path);
  if (opts.name.empty()) opts.name = name_from_file(opts.name_file, opts.idle_exit_s, timed_out);
  if (timed_out) return idle_end();
  if (opts.name.empty()) return 1;
  // The start screen: asked in the plain terminal, before the game takes it over.
  while (!opts.room) {
    std::cout << start_menu_text(term::size().cols) << "> " << std::flush;
    std::string line;
    if (!read_line(line, opts.idle_exit_s, timed_out)) return timed_out ? idle_end() : 1;
    const auto choice = parse_start_choice(line);
    if (const auto* bad = std::get_if<std::string>(&choice)) std::cout << *bad << "\n";
    else opts.room = std::get<RoomChoice>(choice);
  }
  if (!term::enter(opts.kitty, opts.mouse)) {
    std::cerr << "fts-client: needs a terminal (stdin and stdout must be a tty)\n";
    return 1;
  }
  GameEnd end = play(io, opts, *server);
  term::leave();
  if (!opts.stats_file.empty() && !end.stats_json.empty()) {
    if (!write_stats_file(opts.stats_file, end.stats_json)) end.message += (end.message.empty() ? "" : "; ") + std::string("cannot write ") + opts.stats_file;
  }
  if (!end.message.empty()) std::cerr << "fts-client: " << end.message << "\n";
  return end.code;
}
