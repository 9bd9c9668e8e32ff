#include "ui/start_screen.hpp"

#include "ui/panel.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

namespace fts::client {
namespace {

bool is_code(std::string& code) {
  if (code.size() != 5) return false;
  for (char& c : code) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    if (c < 'A' || c > 'Z' || c == 'I' || c == 'L' || c == 'O') return false;
  }
  return true;
}

}  // namespace

std::string start_menu_text(int cols) {
  static constexpr const char* kLines[] = {
      "Fear The Sphere: pick a room",
      "  1 (or Enter)  quick play: the fullest open room, or a new one",
      "  2             create a private room (friends join with its code)",
      "  3 CODE        join a room by its code, e.g. 3 KXBQT",
      "  4 CODE        spectate a room",
      "Once connected, the message log lists the public rooms (code, players, level, phase).",
  };
  // Each line wrapped at spaces to the terminal's width (a word is never broken where
  // it fits on a row), a choice's continuation under its description.
  std::string out;
  for (const std::string line : kLines) {
    const std::size_t indent = line.rfind("  ", 0) == 0 ? 16 : 0;
    const int width = std::max(cols, 20);
    std::vector<std::string> rows = wrap(line, width);
    if (indent > 0 && rows.size() > 1) {
      const std::string rest = line.substr(rows.front().size() + 1);
      rows.resize(1);
      for (auto& part : wrap(rest, width - static_cast<int>(indent))) rows.push_back(std::string(indent, ' ') + part);
    }
    for (const auto& row : rows) out += row + "\n";
  }
  return out;
}

std::variant<RoomChoice, std::string> parse_start_choice(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  if (words.empty()) return RoomChoice{};
  const std::string& k = words[0];
  if ((k == "1" || k == "q" || k == "quick") && words.size() == 1) return RoomChoice{};
  if ((k == "2" || k == "c" || k == "create") && words.size() == 1) return RoomChoice{"create", ""};
  const bool join = k == "3" || k == "j" || k == "join";
  const bool spectate = k == "4" || k == "s" || k == "spectate";
  if (join || spectate) {
    if (words.size() != 2) return std::string("give the room's code after ") + k + ", e.g. " + k + " KXBQT";
    std::string code = words[1];
    if (!is_code(code)) return "'" + words[1] + "' is not a room code (5 letters, no I, L or O)";
    return RoomChoice{join ? "join" : "spectate", code};
  }
  return std::string("type 1, 2, 3 CODE or 4 CODE");
}

std::string room_label(const std::string& code, bool spectator) {
  if (code.empty()) return "";
  return (spectator ? "Watching " : "Room ") + code;
}

}  // namespace fts::client
