#include "ui/fine_field.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace fts::client {

namespace {

// The dots of the platform and its one-cell frame, each owned by the ball drawn on it.
class DotGrid {
 public:
  explicit DotGrid(const Viewport& v)
      : v_(v), cols_((v.cols + 2) * kDotsPerCol), rows_((v.rows + 2) * kDotsPerRow),
        owner_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_), -1) {}

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  // Arena coordinates of a dot's centre (dot 0 is in the frame's cell).
  double x_of(int i) const { return (i - kDotsPerCol + 0.5) * v_.units_per_col() / kDotsPerCol; }
  double y_of(int j) const { return v_.height_u - (j - kDotsPerRow + 0.5) * v_.units_per_row() / kDotsPerRow; }
  // The dot column of arena x and the dot row of arena y (clamped far outside).
  int i_of(double x) const { return index_of(x / (v_.units_per_col() / kDotsPerCol)) + kDotsPerCol; }
  int j_of(double y) const { return index_of((v_.height_u - y) / (v_.units_per_row() / kDotsPerRow)) + kDotsPerRow; }
  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < cols_ && j < rows_; }
  int& set(int i, int j) { return owner_[static_cast<std::size_t>(j) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(i)]; }
  // The ball owning the dot, -1 for none or outside.
  int at(int i, int j) const {
    return inside(i, j) ? owner_[static_cast<std::size_t>(j) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(i)] : -1;
  }
  // The screen cell of a dot.
  int col_of(int i) const { return v_.col0 - 1 + i / kDotsPerCol; }
  int row_of(int j) const { return v_.row0 - 1 + j / kDotsPerRow; }

 private:
  static int index_of(double v) {
    if (!(v > -1e6)) return -1'000'000;
    if (!(v < 1e6)) return 1'000'000;
    return static_cast<int>(std::floor(v));
  }
  Viewport v_;
  int cols_, rows_;
  std::vector<int> owner_;
};

}  // namespace

void draw_balls_fine(Screen& s, const Viewport& v, FieldCells& cells, const std::vector<FineBall>& balls) {
  DotGrid grid(v);
  // Every dot whose centre lies in a ball's disc is that ball's (at least its centre dot).
  for (std::size_t k = 0; k < balls.size(); ++k) {
    const protocol::BallState& b = *balls[k].ball;
    if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.radius)) continue;
    const double r = std::clamp(b.radius, 0.0, 1e6);
    const int i0 = std::max(grid.i_of(b.x - r), 0), i1 = std::min(grid.i_of(b.x + r), grid.cols() - 1);
    const int j0 = std::max(grid.j_of(b.y + r), 0), j1 = std::min(grid.j_of(b.y - r), grid.rows() - 1);
    bool any = false;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double dx = grid.x_of(i) - b.x, dy = grid.y_of(j) - b.y;
        if (dx * dx + dy * dy <= r * r) {
          grid.set(i, j) = static_cast<int>(k);
          any = true;
        }
      }
    const int ci = grid.i_of(b.x), cj = grid.j_of(b.y);
    if (!any && grid.inside(ci, cj)) grid.set(ci, cj) = static_cast<int>(k);  // even a tiny ball shows
  }
  // Apart: a dot beside a dot of a ball drawn later stays empty, so balls that touch (or
  // overlap) show a gap of one dot; the later ball keeps its whole shape.
  std::vector<bool> lit(static_cast<std::size_t>(grid.cols()) * static_cast<std::size_t>(grid.rows()), false);
  for (int j = 0; j < grid.rows(); ++j)
    for (int i = 0; i < grid.cols(); ++i) {
      const int a = grid.at(i, j);
      if (a < 0) continue;
      const bool beside_later = grid.at(i - 1, j) > a || grid.at(i + 1, j) > a || grid.at(i, j - 1) > a || grid.at(i, j + 1) > a;
      lit[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.cols()) + static_cast<std::size_t>(i)] = !beside_later;
    }
  // Each cell: its lit dots, in the colour of the ball with most of them (the later on a tie).
  std::vector<int> count(balls.size(), 0);
  for (int cj = 0; cj < grid.rows() / kDotsPerRow; ++cj)
    for (int ci = 0; ci < grid.cols() / kDotsPerCol; ++ci) {
      std::uint8_t dots = 0;
      int best = -1;
      for (int y = 0; y < kDotsPerRow; ++y)
        for (int x = 0; x < kDotsPerCol; ++x) {
          const int i = ci * kDotsPerCol + x, j = cj * kDotsPerRow + y;
          const int a = grid.at(i, j);
          if (a < 0 || !lit[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.cols()) + static_cast<std::size_t>(i)]) continue;
          dots = static_cast<std::uint8_t>(dots | braille_bit(x, y));
          const int n = ++count[static_cast<std::size_t>(a)];
          if (best < 0 || n > count[static_cast<std::size_t>(best)] || (n == count[static_cast<std::size_t>(best)] && a > best)) best = a;
        }
      for (int y = 0; y < kDotsPerRow; ++y)
        for (int x = 0; x < kDotsPerCol; ++x)
          if (const int a = grid.at(ci * kDotsPerCol + x, cj * kDotsPerRow + y); a >= 0) count[static_cast<std::size_t>(a)] = 0;
      if (best < 0) continue;
      const int col = grid.col_of(ci * kDotsPerCol), row = grid.row_of(cj * kDotsPerRow);
      s.set_dots(col, row, dots, balls[static_cast<std::size_t>(best)].style);
      cells.cover(col, row, best);
    }
  // The mass, centred on the ball's middle row, on cells the ball fills entirely (black
  // on the ball's colour), and only where some of the ball still shows beside it.
  for (std::size_t k = 0; k < balls.size(); ++k) {
    const protocol::BallState& b = *balls[k].ball;
    if (!balls[k].label || !std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.mass)) continue;
    const std::string label = std::to_string(std::llround(std::clamp(b.mass, 0.0, 1e9)));
    const int n = static_cast<int>(label.size());
    const int cc = v.col_of(b.x), rc = v.row_of(b.y);
    const int start = cc - (n - 1) / 2;
    if (cells.cells_of(static_cast<int>(k)) <= n) continue;
    bool fits = true;
    for (int i = 0; i < n && fits; ++i) {
      const int col = start + i;
      fits = cells.ball_at(col, rc) == static_cast<int>(k) && s.inside(col, rc) && s.at(col, rc).braille() &&
             s.at(col, rc).dots == 0xFF;
    }
    if (!fits) continue;
    const Style st{Color::black, balls[k].style.fg, true, false, false};
    s.put(start, rc, label, st);
  }
}

}  // namespace fts::client
