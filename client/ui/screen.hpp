// A terminal frame as a grid of cells with colours, built by the pure renderer and turned
// into ANSI escape sequences (or plain text) by to_ansi. No I/O here.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fts::client {

struct TerminalSize {
  int cols = 80;
  int rows = 24;
};

enum class Color : std::uint8_t {
  none, black, red, green, yellow, blue, magenta, cyan, white, gray,
  bright_green, bright_blue, bright_magenta, bright_cyan, bright_yellow
};

struct Style {
  Color fg = Color::none;
  Color bg = Color::none;
  bool bold = false;
  bool dim = false;
  bool underline = false;
  bool operator==(const Style&) const = default;
};

struct Cell {
  char ch = ' ';  // printable ASCII only: what reaches the terminal is ours
  Style style;
  bool operator==(const Cell&) const = default;
};

class Screen {
 public:
  explicit Screen(TerminalSize size);

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  bool inside(int col, int row) const { return col >= 0 && row >= 0 && col < cols_ && row < rows_; }
  const Cell& at(int col, int row) const { return cells_[index(col, row)]; }
  // Sets one cell; outside the screen it does nothing. Non-printable characters become '?'.
  void set(int col, int row, char ch, Style style = {});
  // Writes text from (col, row), clipped at the right edge; returns the column after it.
  int put(int col, int row, std::string_view text, Style style = {});
  // One row as plain text (trailing spaces kept).
  std::string line(int row) const;
  std::vector<std::string> lines() const;

 private:
  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col);
  }
  int cols_;
  int rows_;
  std::vector<Cell> cells_;
};

// The whole frame as bytes for the terminal: cursor home, every row, styles as SGR
// sequences when `color` is true, plain characters otherwise.
std::string to_ansi(const Screen& screen, bool color);

// Colour unless NO_COLOR is set (to anything non-empty) or TERM is "dumb".
bool color_wanted(const char* no_color_env, const char* term_env);

}  // namespace fts::client
