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

void Screen::set_dots(int col, int row, std::uint8_t dots, Style style) {
  if (!inside(col, row)) return;
  cells_[index(col, row)] = Cell{'\0', style, dots};
}

std::string braille_utf8(std::uint8_t dots) {
  // U+2800 + dots: 1110 0010, 10 1000 dd, 10 dddddd.
  return {static_cast<char>(0xE2), static_cast<char>(0xA0 | (dots >> 6)), static_cast<char>(0x80 | (dots & 0x3F))};
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
  for (int c = 0; c < cols_; ++c) {
    const Cell& cell = at(c, row);
    if (cell.braille()) out += braille_utf8(cell.dots);
    else out += cell.ch;
  }
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

std::string ansi_row(const Screen& screen, int r, bool color) {
  std::string out = "\x1b[" + std::to_string(r + 1) + ";1H";
  Style current;
  if (color) out += "\x1b[0m";
  for (int c = 0; c < screen.cols(); ++c) {
    const Cell& cell = screen.at(c, r);
    if (color && !(cell.style == current)) {
      out += sgr(cell.style);
      current = cell.style;
    }
    if (cell.braille()) out += braille_utf8(cell.dots);
    else out += cell.ch;
  }
  return out;
}

std::string repaint(const Screen& screen, std::vector<std::string>& last_rows, bool color) {
  std::string out;
  last_rows.resize(static_cast<std::size_t>(screen.rows()));
  for (int r = 0; r < screen.rows(); ++r) {
    std::string row = ansi_row(screen, r, color);
    std::string& last = last_rows[static_cast<std::size_t>(r)];
    if (row == last) continue;
    out += row;
    last = std::move(row);
  }
  if (!out.empty() && color) out += "\x1b[0m";
  return out;
}

std::string to_ansi(const Screen& screen, bool color) {
  std::string out = "\x1b[H";
  for (int r = 0; r < screen.rows(); ++r) out += ansi_row(screen, r, color);
  if (color) out += "\x1b[0m";
  return out;
}

bool braille_wanted(const char* lc_all, const char* lc_ctype, const char* lang, const char* term_env) {
  const char* locale = "";
  for (const char* v : {lc_all, lc_ctype, lang})
    if (v != nullptr && v[0] != '\0') {
      locale = v;
      break;
    }
  std::string lower;
  for (const char* c = locale; *c != '\0'; ++c) lower += static_cast<char>(*c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
  if (lower.find("utf-8") == std::string::npos && lower.find("utf8") == std::string::npos) return false;
  const std::string_view term = term_env != nullptr ? term_env : "";
  return !term.empty() && term != "dumb" && term != "linux" && term.substr(0, 2) != "vt";
}

bool color_wanted(const char* no_color_env, const char* term_env) {
  if (no_color_env != nullptr && no_color_env[0] != '\0') return false;
  if (term_env != nullptr && std::string_view(term_env) == "dumb") return false;
  return true;
}

}  // namespace fts::client
