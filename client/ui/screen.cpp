#include "ui/screen.hpp"

#include <algorithm>

namespace fts::client {

Screen::Screen(TerminalSize size)
    : cols_(std::max(size.cols, 1)), rows_(std::max(size.rows, 1)),
      cells_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_)) {}

void Screen::set(int col, int row, char ch, Style style) {
  if (!inside(col, row)) return;
  const bool printable = ch >= 0x20 && ch < 0x7f;
  cells_[index(col, row)] = Cell{printable ? ch : '?', style};
}

int Screen::put(int col, int row, std::string_view text, Style style) {
  for (char ch : text) {
    set(col, row, ch, style);
    ++col;
  }
  return col;
}

std::string Screen::line(int row) const {
  std::string out;
  if (row < 0 || row >= rows_) return out;
  out.reserve(static_cast<std::size_t>(cols_));
  for (int c = 0; c < cols_; ++c) out += at(c, row).ch;
  return out;
}

std::vector<std::string> Screen::lines() const {
  std::vector<std::string> out;
  for (int r = 0; r < rows_; ++r) out.push_back(line(r));
  return out;
}

namespace {

int color_code(Color c) {
  switch (c) {
    case Color::none: return -1;
    case Color::black: return 0;
    case Color::red: return 1;
    case Color::green: return 2;
    case Color::yellow: return 3;
    case Color::blue: return 4;
    case Color::magenta: return 5;
    case Color::cyan: return 6;
    case Color::white: return 7;
    case Color::gray: return 60;  // bright black: 90 / 100
    case Color::bright_green: return 62;
    case Color::bright_blue: return 64;
    case Color::bright_magenta: return 65;
    case Color::bright_cyan: return 66;
    case Color::bright_yellow: return 63;
  }
  return -1;
}

std::string sgr(const Style& s) {
  std::string out = "\x1b[0";
  if (s.bold) out += ";1";
  if (s.dim) out += ";2";
  if (s.underline) out += ";4";
  if (const int f = color_code(s.fg); f >= 0) out += ";" + std::to_string(30 + f);
  if (const int b = color_code(s.bg); b >= 0) out += ";" + std::to_string(40 + b);
  return out + "m";
}

}  // namespace

std::string to_ansi(const Screen& screen, bool color) {
  std::string out = "\x1b[H";
  for (int r = 0; r < screen.rows(); ++r) {
    out += "\x1b[" + std::to_string(r + 1) + ";1H";
    Style current;
    if (color) out += "\x1b[0m";
    for (int c = 0; c < screen.cols(); ++c) {
      const Cell& cell = screen.at(c, r);
      if (color && !(cell.style == current)) {
        out += sgr(cell.style);
        current = cell.style;
      }
      out += cell.ch;
    }
  }
  if (color) out += "\x1b[0m";
  return out;
}

bool color_wanted(const char* no_color_env, const char* term_env) {
  if (no_color_env != nullptr && no_color_env[0] != '\0') return false;
  if (term_env != nullptr && std::string_view(term_env) == "dumb") return false;
  return true;
}

}  // namespace fts::client
