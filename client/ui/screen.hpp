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
  char ch = ' ';  // printable ASCII only: what reaches the terminal is ours; '\0': braille
  Style style;
  std::uint8_t dots = 0;  // a braille cell's dots (bit k is dot k + 1 of U+2800)
  bool braille() const { return ch == '\0'; }
  bool operator==(const Cell&) const = default;
};

// A braille cell's dot bit for the dot at (x, y): x 0..1 left to right, y 0..3 top down.
constexpr std::uint8_t braille_bit(int x, int y) {
  constexpr std::uint8_t kBits[2][4] = {{0x01, 0x02, 0x04, 0x40}, {0x08, 0x10, 0x20, 0x80}};
  return kBits[x & 1][y & 3];
}
// The UTF-8 bytes of the braille pattern with these dots (U+2800 + dots).
std::string braille_utf8(std::uint8_t dots);

class Screen {
 public:
  explicit Screen(TerminalSize size);

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  bool inside(int col, int row) const { return col >= 0 && row >= 0 && col < cols_ && row < rows_; }
  const Cell& at(int col, int row) const { return cells_[index(col, row)]; }
  // Sets one cell; outside the screen it does nothing. Non-printable characters become '?'.
  void set(int col, int row, char ch, Style style = {});
  // Makes the cell a braille pattern (the fine field, ui/fine_field.hpp).
  void set_dots(int col, int row, std::uint8_t dots, Style style = {});
  // Writes text from (col, row), clipped at the right edge; returns the column after it.
  int put(int col, int row, std::string_view text, Style style = {});
  // One row as plain text (trailing spaces kept; a braille cell as its UTF-8 bytes).
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

// One row as bytes for the terminal: the cursor to its start, its cells with their styles
// as SGR sequences when `color` is true (starting from no style), plain otherwise.
std::string ansi_row(const Screen& screen, int row, bool color);

// The bytes that turn the frame whose rows were `last_rows` (ansi_row's, updated here)
// into `screen`: the rows that differ, then no style. Empty when nothing changed.
std::string repaint(const Screen& screen, std::vector<std::string>& last_rows, bool color);

// The whole frame as bytes for the terminal: cursor home, every row, styles as SGR
// sequences when `color` is true, plain characters otherwise.
std::string to_ansi(const Screen& screen, bool color);

// The field in braille dots (--glyphs auto): when the locale's characters are UTF-8
// (the first set of LC_ALL, LC_CTYPE, LANG names UTF-8) and TERM is a terminal that
// draws them (not dumb, not the Linux console, not a vt100-style one).
bool braille_wanted(const char* lc_all, const char* lc_ctype, const char* lang, const char* term_env);

// Colour unless NO_COLOR is set (to anything non-empty) or TERM is "dumb".
bool color_wanted(const char* no_color_env, const char* term_env);

}  // namespace fts::client
