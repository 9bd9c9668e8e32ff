#include "ui/layout.hpp"

#include <algorithm>
#include <cmath>

namespace fts::client {

namespace {
// floor(v) as an int, clamped far outside any screen (NaN counts as far outside).
int cell_index(double v) {
  if (!(v > -1e6)) return -1'000'000;
  if (!(v < 1e6)) return 1'000'000;
  return static_cast<int>(std::floor(v));
}
}  // namespace

int Viewport::col_of(double x_u) const { return col0 + cell_index(x_u / width_u * cols); }

int Viewport::row_of(double y_u) const {
  // y = height maps to the first row; y = 0 to just below the last row. A point exactly
  // on the top edge belongs to the top row.
  return row0 + cell_index((height_u - y_u) / height_u * rows);
}

double Viewport::x_of(int col) const { return (col - col0 + 0.5) * units_per_col(); }

double Viewport::y_of(int row) const { return height_u - (row - row0 + 0.5) * units_per_row(); }

Viewport fit_arena(int col0, int row0, int cols, int rows, double width_u, double height_u,
                   double cell_aspect) {
  Viewport v;
  // Sizes come from the network: anything not a sane positive number becomes 500 x 300.
  const bool sane = std::isfinite(width_u) && std::isfinite(height_u) && width_u > 0 && height_u > 0 &&
                    width_u < 1e9 && height_u < 1e9;
  v.width_u = sane ? width_u : 500;
  v.height_u = sane ? height_u : 300;
  cols = std::max(cols, 1);
  rows = std::max(rows, 1);
  // Units per column; a row covers cell_aspect times as many units.
  const double s = std::max(v.width_u / cols, v.height_u / (cell_aspect * rows));
  v.cols = std::clamp(static_cast<int>(std::lround(v.width_u / s)), 1, cols);
  v.rows = std::clamp(static_cast<int>(std::lround(v.height_u / (cell_aspect * s))), 1, rows);
  v.col0 = col0 + (cols - v.cols) / 2;
  v.row0 = row0 + (rows - v.rows) / 2;
  return v;
}

}  // namespace fts::client
