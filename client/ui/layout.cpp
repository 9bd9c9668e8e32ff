#include "ui/layout.hpp"

#include <algorithm>
#include <cmath>

namespace fts::client {

int Viewport::col_of(double x_u) const {
  return col0 + static_cast<int>(std::floor(x_u / width_u * cols));
}

int Viewport::row_of(double y_u) const {
  // y = height maps to the first row; y = 0 to just below the last row. A point exactly
  // on the top edge belongs to the top row.
  const double from_top = (height_u - y_u) / height_u * rows;
  return row0 + static_cast<int>(std::floor(from_top));
}

double Viewport::x_of(int col) const { return (col - col0 + 0.5) * units_per_col(); }

double Viewport::y_of(int row) const { return height_u - (row - row0 + 0.5) * units_per_row(); }

Viewport fit_arena(int col0, int row0, int cols, int rows, double width_u, double height_u,
                   double cell_aspect) {
  Viewport v;
  v.width_u = width_u > 0 ? width_u : 1;
  v.height_u = height_u > 0 ? height_u : 1;
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
