// Where the platform goes on the terminal: scaled to fit the space it is given, with the
// platform's aspect ratio kept although a terminal cell is about twice as tall as wide.
#pragma once

namespace fts::client {

inline constexpr double kCellAspect = 2.0;  // cell height / cell width

// A rectangle of cells showing the arena [0, width_u] x [0, height_u] (y grows up).
struct Viewport {
  int col0 = 0, row0 = 0;  // top-left cell of the platform
  int cols = 1, rows = 1;  // size in cells
  double width_u = 500, height_u = 300;

  // The cell column of arena x and the cell row of arena y (rows grow downwards). Points
  // on or outside the edges map to the cells beyond the platform.
  int col_of(double x_u) const;
  int row_of(double y_u) const;
  // Arena coordinates of a cell's centre.
  double x_of(int col) const;
  double y_of(int row) const;
  double units_per_col() const { return width_u / cols; }
  double units_per_row() const { return height_u / rows; }
};

// The largest platform that fits in the area (col0, row0, cols x rows), centred in it.
Viewport fit_arena(int col0, int row0, int cols, int rows, double width_u, double height_u,
                   double cell_aspect = kCellAspect);

}  // namespace fts::client
