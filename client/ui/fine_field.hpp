// The field drawn finer (issue 37): each cell of the platform is a braille pattern of 2x4
// dots, so a ball's edge moves a quarter of a row and half a column at a time instead of
// a whole cell, keeps its round shape at 80x24, and two balls an edge apart keep a row of
// empty dots between them. A cell shows one colour: the colour of the ball with most
// dots in it. Plain ASCII (render.cpp) stays for terminals without UTF-8 or colour.
#pragma once

#include <utility>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "ui/field_cells.hpp"
#include "ui/layout.hpp"
#include "ui/screen.hpp"

namespace fts::client {

// Dots per cell across and down.
inline constexpr int kDotsPerCol = 2;
inline constexpr int kDotsPerRow = 4;

// One ball to draw and its colour; a later ball is drawn over an earlier one.
struct FineBall {
  const protocol::BallState* ball = nullptr;
  Style style;
  bool label = true;  // its mass written in it where the digits fit on whole cells
};

// Draws the balls in order as dots on the platform and its frame, records in `cells` the
// cells each ball shows most of (the names go around them), and writes each mass on the
// ball's middle row where its digits fall on cells the ball fills entirely.
void draw_balls_fine(Screen& s, const Viewport& v, FieldCells& cells, const std::vector<FineBall>& balls);

}  // namespace fts::client
