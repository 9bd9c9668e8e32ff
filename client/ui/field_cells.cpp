#include "ui/field_cells.hpp"

#include <algorithm>
#include <cstdlib>

namespace fts::client {

FieldCells::FieldCells(const Viewport& v)
    : col0_(v.col0 - 1), row0_(v.row0 - 1), cols_(std::max(v.cols, 0) + 2), rows_(std::max(v.rows, 0) + 2),
      ball_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_), -1),
      name_(ball_.size(), false) {}

std::size_t FieldCells::index(int col, int row) const {
  return static_cast<std::size_t>(row - row0_) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col - col0_);
}

bool FieldCells::on_field(int col, int row) const {
  return col >= col0_ && row >= row0_ && col < col0_ + cols_ && row < row0_ + rows_;
}

bool FieldCells::on_platform(int col, int row) const {
  return col > col0_ && row > row0_ && col < col0_ + cols_ - 1 && row < row0_ + rows_ - 1;
}

int FieldCells::ball_at(int col, int row) const { return on_field(col, row) ? ball_[index(col, row)] : -1; }

bool FieldCells::named(int col, int row) const { return on_field(col, row) && name_[index(col, row)]; }

int FieldCells::cells_of(int ball) const {
  return ball >= 0 && static_cast<std::size_t>(ball) < counts_.size() ? counts_[static_cast<std::size_t>(ball)] : 0;
}

void FieldCells::cover(int col, int row, int ball) {
  if (!on_field(col, row) || ball < 0) return;
  const auto b = static_cast<std::size_t>(ball);
  if (b >= boxes_.size()) {
    boxes_.resize(b + 1);
    counts_.resize(b + 1, 0);
  }
  int& cell = ball_[index(col, row)];
  if (cell == ball) return;
  if (cell >= 0) --counts_[static_cast<std::size_t>(cell)];
  cell = ball;
  ++counts_[b];
  Box& box = boxes_[b];
  if (box.col1 < box.col0) {
    box = {col, col, row, row};
  } else {
    box.col0 = std::min(box.col0, col);
    box.col1 = std::max(box.col1, col);
    box.row0 = std::min(box.row0, row);
    box.row1 = std::max(box.row1, row);
  }
}

FieldCells::Span FieldCells::span(int ball, int row) const {
  Span s;
  const Box& box = boxes_[static_cast<std::size_t>(ball)];
  for (int col = box.col0; col <= box.col1; ++col) {
    if (ball_at(col, row) != ball) continue;
    if (s.empty()) s = {col, col};
    else s.col1 = col;
  }
  return s;
}

bool FieldCells::free_for(int ball, int col, int row, int length, bool strict) const {
  if (named(col - 1, row) || named(col + length, row)) return false;  // names stay apart
  for (int c = col; c < col + length; ++c) {
    if (!on_platform(c, row) || ball_at(c, row) >= 0 || named(c, row)) return false;
    if (!strict) continue;
    for (const auto& [dc, dr] : {std::pair{0, -1}, std::pair{0, 1}, std::pair{-1, 0}, std::pair{1, 0}}) {
      const int other = ball_at(c + dc, row + dr);
      if (other >= 0 && other != ball) return false;
    }
  }
  return true;
}

std::optional<LabelSpot> FieldCells::find_spot(int ball, int length, bool strict) const {
  if (length <= 0 || cells_of(ball) <= 0) return std::nullopt;
  const Box& box = boxes_[static_cast<std::size_t>(ball)];
  // The ball's top and bottom rows that still show it.
  int top = box.row1 + 1, bottom = box.row0 - 1;
  for (int row = box.row0; row <= box.row1; ++row) {
    if (span(ball, row).empty()) continue;
    top = std::min(top, row);
    bottom = std::max(bottom, row);
  }
  if (top > bottom) return std::nullopt;
  // Above or below: centred on the ball's edge row, shifted as little as needed, but
  // always over at least one of that row's cells (so it touches the ball).
  const auto on_row = [&](int edge_row, int row) -> std::optional<LabelSpot> {
    const Span s = span(ball, edge_row);
    if (s.empty()) return std::nullopt;
    const int start = (s.col0 + s.col1 + 1) / 2 - length / 2;
    const int reach = length + (s.col1 - s.col0);
    for (int k = 0; k <= 2 * reach; ++k) {
      const int col = start + (k % 2 == 1 ? (k + 1) / 2 : -(k / 2));  // start, +1, -1, +2, -2, ...
      if (col > s.col1 || col + length - 1 < s.col0) continue;
      if (free_for(ball, col, row, length, strict)) return LabelSpot{col, row};
    }
    return std::nullopt;
  };
  if (auto spot = on_row(top, top - 1)) return spot;
  if (auto spot = on_row(bottom, bottom + 1)) return spot;
  // Right or left: on the ball's middle row, just past its edge.
  const int mid = (top + bottom) / 2;
  const Span s = span(ball, mid);
  if (!s.empty()) {
    if (free_for(ball, s.col1 + 1, mid, length, strict)) return LabelSpot{s.col1 + 1, mid};
    if (free_for(ball, s.col0 - length, mid, length, strict)) return LabelSpot{s.col0 - length, mid};
  }
  return std::nullopt;
}

void FieldCells::take(LabelSpot spot, int length) {
  for (int c = spot.col; c < spot.col + length; ++c)
    if (on_field(c, spot.row)) name_[index(c, spot.row)] = true;
}

}  // namespace fts::client
