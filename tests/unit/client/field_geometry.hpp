// The cells a ball is drawn on, from its geometry alone (the renderer's rule: every cell
// of the platform and its frame whose centre lies in the disc, and the centre cell), so
// that the tests can check the screen against where the balls are.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "ui/layout.hpp"

namespace fts::client::test {

inline bool on_field(const Viewport& v, int col, int row) {
  return col >= v.col0 - 1 && col <= v.col0 + v.cols && row >= v.row0 - 1 && row <= v.row0 + v.rows;
}

inline std::vector<std::pair<int, int>> disc_cells(const Viewport& v, const protocol::BallState& b) {
  std::vector<std::pair<int, int>> out;
  for (int row = v.row0 - 1; row <= v.row0 + v.rows; ++row)
    for (int col = v.col0 - 1; col <= v.col0 + v.cols; ++col) {
      const double dx = v.x_of(col) - b.x, dy = v.y_of(row) - b.y;
      if (dx * dx + dy * dy <= b.radius * b.radius) out.emplace_back(col, row);
    }
  const std::pair<int, int> centre{v.col_of(b.x), v.row_of(b.y)};
  if (on_field(v, centre.first, centre.second) && std::find(out.begin(), out.end(), centre) == out.end())
    out.push_back(centre);
  return out;
}

// The top row of a ball's cells (-1 when it shows none).
inline int top_row(const Viewport& v, const protocol::BallState& b) {
  int top = -1;
  for (const auto& [col, row] : disc_cells(v, b))
    if (top < 0 || row < top) top = row;
  return top;
}

}  // namespace fts::client::test
