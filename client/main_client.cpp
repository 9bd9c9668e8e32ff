// fts-client: the program. Options, the replay mode, the server's address, the start
// screen in the plain terminal, then the game (game.cpp) in the raw one, and at the end
// the terminal given back and --stats-file written.
#include <fstream>
#include <iostream>
#include <string>
#include <variant>

#include "client_options.hpp"
#include "game.hpp"
#include "replay/replay_loop.hpp"
#include "term/terminal.hpp"
#include "ui/start_screen.hpp"

using namespace fts::client;

int main(int argc, char** argv) {
  Options opts;
  if (const int code = parse_options(argc, argv, opts); code >= 0) return code;
  if (!opts.replay.empty()) {
    std::string message;
    const int code = run_replay(opts.replay, opts.kitty, message);
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
  // The start screen: asked in the plain terminal, before the game takes it over.
  while (!opts.room) {
    std::cout << start_menu_text() << "> " << std::flush;
    std::string line;
    if (!std::getline(std::cin, line)) return 1;
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
    std::ofstream out(opts.stats_file);
    out << end.stats_json << "\n";
    if (!out) end.message += (end.message.empty() ? "" : "; ") + std::string("cannot write ") + opts.stats_file;
  }
  if (!end.message.empty()) std::cerr << "fts-client: " << end.message << "\n";
  return end.code;
}
