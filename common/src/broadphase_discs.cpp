#include "fts/sim/broadphase_discs.hpp"

#include <algorithm>
#include <cmath>

#include "lanes.hpp"

namespace fts::sim {
namespace {

constexpr std::uint32_t kGiant = 0xffffffffu;
// Cell width in largest diameters. 1 is the least that keeps the stencil complete;
// wider cells mean fewer (mostly empty) cells to count and more discs per range.
constexpr double kCellDiameters = 2.0;
// A disc wider than this many mean diameters is a giant.
constexpr double kGiantFactor = 4.0;
// Window widths (slots tested without branches) for the two ranges of the stencil;
// longer ranges are walked. With 2-diameter cells of the gas (about one disc per cell)
// the right range holds 1.5 discs on average, the upper one 3.
constexpr std::uint32_t kDiscRightWindow = 4;
constexpr std::uint32_t kDiscUpWindow = 6;
constexpr std::uint32_t kWindowPad = kDiscUpWindow;
constexpr double kFar = 1e300;

}  // namespace

void DiscGrid::file(const std::vector<Ball>& balls, const DiscBounds& bounds) {
  const std::size_t n = balls.size();
  cell_.resize(n);
  giants_.clear();
  // The usual case (no giant) needs nothing more than the bounds: mean and largest
  // radius, centre bounds.
  double mean_r = bounds.sum_r / static_cast<double>(n);
  if (!(mean_r > 0.0) || !std::isfinite(mean_r)) mean_r = 1.0;
  const double giant_r = kGiantFactor * mean_r;
  const bool has_giants = !(bounds.r_max <= giant_r);
  DiscBounds f = bounds;  // of the filed discs
  if (has_giants) {
    // Set the giants aside; the cells and bounds come from the others.
    f = {};
    for (std::size_t i = 0; i < n; ++i) {
      const Ball& b = balls[i];
      if (!(b.radius <= giant_r)) {
        cell_[i] = kGiant;
        giants_.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      cell_[i] = 0;
      f.add(b);
    }
  }
  grid_ = GridLayout::fit(f.lo_x, f.hi_x, f.lo_y, f.hi_y, kCellDiameters * 2.0 * f.r_max, n);

  // Counting sort over the padded cells: start_[c + 1] counts cell c, then (prefix sum)
  // marks its end; filing from the last disc down moves it to the cell's beginning,
  // discs in index order. So cell c is [start_[c + 1], start_[c + 2]).
  stride_ = grid_.nx + 2;
  const std::size_t ncells = static_cast<std::size_t>(stride_) * (grid_.ny + 2);
  start_.assign(ncells + 2, 0);
  const GridLayout grid = grid_;
  const std::uint32_t stride = stride_;
  std::uint32_t* count = start_.data() + 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (has_giants && cell_[i] == kGiant) continue;
    const Ball& b = balls[i];
    const std::uint32_t c = (grid.row(b.pos.y) + 1) * stride + grid.column(b.pos.x) + 1;
    cell_[i] = c;
    ++count[c];
  }
  for (std::size_t c = 1; c <= ncells; ++c) start_[c] += start_[c - 1];
  const std::uint32_t filed = start_[ncells];
  start_[ncells + 1] = filed;
  // The padding is far from everything (its squared distances overflow to infinity),
  // so a window that reads it finds nothing there.
  for (auto [v, pad] : {std::pair{&x_, kFar}, std::pair{&y_, kFar}, std::pair{&r_, 0.0}}) {
    v->resize(filed + kWindowPad);
    std::fill(v->begin() + filed, v->end(), pad);
  }
  id_.resize(filed);
  slot_cell_.resize(filed);
  double* xs = x_.data();
  double* ys = y_.data();
  double* rs = r_.data();
  // First only the ball indices in cell order (one small array: random writes stay in
  // cache even for 10^5 discs), then the discs gathered in that order: sequential
  // writes, one ball read each, fetched a few slots ahead.
  std::uint32_t* ids = id_.data();
  for (std::size_t i = n; i-- > 0;) {
    const std::uint32_t c = cell_[i];
    if (has_giants && c == kGiant) continue;
    ids[--count[c]] = static_cast<std::uint32_t>(i);
  }
  const Ball* bs = balls.data();
  std::uint32_t* cells = slot_cell_.data();
  constexpr std::uint32_t kAhead = 8;
  for (std::uint32_t q = 0; q < filed; ++q) {
    if (q + kAhead < filed) __builtin_prefetch(bs + ids[q + kAhead]);
    const std::uint32_t i = ids[q];
    const Ball& b = bs[i];
    xs[q] = b.pos.x;
    ys[q] = b.pos.y;
    rs[q] = b.radius;
    cells[q] = cell_[i];
  }
}

namespace {

// Whether any of the kWidth slots from `from` touches the disc (x, y, r), two at a time
// and without a branch. The window may reach past the range the caller wants tested:
// a touching disc there only costs a walk of the range, which tests exactly.
template <std::uint32_t kWidth>
bool window_touches(const double* xs, const double* ys, const double* rs, std::uint32_t from, double x, double y,
                    double r) {
  static_assert(kWidth % 2 == 0);
  using detail::D2;
  const D2 vx = {x, x}, vy = {y, y}, vr = {r, r};
  detail::Bits2 hit = {0, 0};
#pragma GCC unroll 8
  for (std::uint32_t k = 0; k < kWidth; k += 2) {
    const D2 dx = detail::lanes(xs + from + k) - vx, dy = detail::lanes(ys + from + k) - vy;
    const D2 reach = detail::lanes(rs + from + k) + vr;
    hit |= (detail::Bits2)(dx * dx + dy * dy <= reach * reach);  // all ones where they touch
  }
  return (hit[0] | hit[1]) != 0;
}

}  // namespace

void DiscGrid::touching_pairs(const std::vector<Ball>& balls, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out,
                              const DiscBounds* bounds) {
  if (balls.empty()) return;
  if (bounds) {
    file(balls, *bounds);
  } else {
    DiscBounds own;
    for (const Ball& b : balls) own.add(b);
    file(balls, own);
  }
  const double* xs = x_.data();
  const double* ys = y_.data();
  const double* rs = r_.data();
  const std::uint32_t* ids = id_.data();
  const std::uint32_t* begin = start_.data() + 1;  // cell c is [begin[c], begin[c + 1])
  const std::uint32_t filed = static_cast<std::uint32_t>(id_.size());
  const std::uint32_t stride = stride_;
  // The exact walk of one range, for the rare window with a touching pair in it.
  auto walk = [&](std::uint32_t p, std::uint32_t from, std::uint32_t end) {
    for (std::uint32_t q = from; q < end; ++q) {
      const double dx = xs[q] - xs[p], dy = ys[q] - ys[p], reach = rs[p] + rs[q];
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(std::min(ids[p], ids[q]), std::max(ids[p], ids[q]));
    }
  };
  for (std::uint32_t p = 0; p < filed; ++p) {
    const std::uint32_t c = slot_cell_[p];
    const double x = xs[p], y = ys[p], r = rs[p];
    // The rest of the own cell and the next one of its row; the three cells above.
    const std::uint32_t right_end = begin[c + 2];
    const std::uint32_t up0 = begin[c + stride - 1], up1 = begin[c + stride + 2];
    const std::uint32_t n_right = right_end - (p + 1), n_up = up1 - up0;
    if (n_right > kDiscRightWindow || window_touches<kDiscRightWindow>(xs, ys, rs, p + 1, x, y, r))
      walk(p, p + 1, right_end);
    if (n_up > kDiscUpWindow || window_touches<kDiscUpWindow>(xs, ys, rs, up0, x, y, r)) walk(p, up0, up1);
  }
  // Giants meet everything: filed discs, then later giants.
  for (std::size_t g = 0; g < giants_.size(); ++g) {
    const std::uint32_t gi = giants_[g];
    const Ball& a = balls[gi];
    for (std::uint32_t q = 0; q < filed; ++q) {
      const double dx = xs[q] - a.pos.x, dy = ys[q] - a.pos.y, reach = a.radius + rs[q];
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(std::min(gi, ids[q]), std::max(gi, ids[q]));
    }
    for (std::size_t h = g + 1; h < giants_.size(); ++h) {
      const Ball& b = balls[giants_[h]];
      const double dx = b.pos.x - a.pos.x, dy = b.pos.y - a.pos.y, reach = a.radius + b.radius;
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(gi, giants_[h]);
    }
  }
}

}  // namespace fts::sim
