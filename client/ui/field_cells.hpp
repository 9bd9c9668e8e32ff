// What each cell of the platform holds while the field is drawn: which ball covers it
// and whether a name took it. Balls are drawn first and record their cells here; each
// name then goes to the first free spot next to its own ball, so a name never covers a
// ball, the frame or another name (issue 26). Pure; the renderer owns one per frame.
#pragma once

#include <optional>
#include <vector>

#include "ui/layout.hpp"

namespace fts::client {

// Where a name starts: its first cell; it runs to the right on that row.
struct LabelSpot {
  int col = 0, row = 0;
};

class FieldCells {
 public:
  // The platform of `v` and its one-cell frame.
  explicit FieldCells(const Viewport& v);

  // On the platform or its frame (where a ball may be drawn).
  bool on_field(int col, int row) const;
  // Inside the frame (where a name may be written).
  bool on_platform(int col, int row) const;
  // The ball covering the cell (the index given to cover), -1 for none or off the field.
  int ball_at(int col, int row) const;
  // How many cells ball `ball` still covers (a later ball may have covered some).
  int cells_of(int ball) const;
  // Ball `ball` (0, 1, 2, ... in drawing order) covers the cell; a later ball covers an
  // earlier one. Off the field it does nothing.
  void cover(int col, int row, int ball);

  // The first free spot for a name of `length` cells next to ball `ball`: above it, below
  // it, right of it, left of it, each on the platform, on no ball, and one cell clear of
  // every other name on its row. With `strict`, the spot also touches no other ball (so
  // that it cannot be read as that ball's). Nothing when the ball shows no cell or no
  // spot is free.
  std::optional<LabelSpot> find_spot(int ball, int length, bool strict) const;
  // The name now holds `length` cells from `spot`.
  void take(LabelSpot spot, int length);

 private:
  struct Box {  // the cells a ball was drawn on, inclusive; empty while col1 < col0
    int col0 = 0, col1 = -1, row0 = 0, row1 = -1;
  };
  struct Span {  // a ball's leftmost and rightmost cell on one row
    int col0 = 0, col1 = -1;
    bool empty() const { return col1 < col0; }
  };
  std::size_t index(int col, int row) const;
  bool named(int col, int row) const;
  Span span(int ball, int row) const;
  bool free_for(int ball, int col, int row, int length, bool strict) const;

  int col0_, row0_, cols_, rows_;  // the field: the platform and its frame
  std::vector<int> ball_;          // per cell: the covering ball, -1 none
  std::vector<bool> name_;         // per cell: a name took it
  std::vector<Box> boxes_;         // per ball
  std::vector<int> counts_;        // per ball: the cells it still covers
};

}  // namespace fts::client
