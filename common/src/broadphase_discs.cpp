#include "fts/sim/broadphase_discs.hpp"

#include <algorithm>
#include <cmath>

namespace fts::sim {
namespace {

constexpr std::uint32_t kGiant = 0xffffffffu;
// Cell width in largest diameters. 1 is the least that keeps the stencil complete;
// wider cells mean fewer (mostly empty) cells to count and more discs per range.
constexpr double kCellDiameters = 2.0;
// A disc wider than this many mean diameters is a giant.
constexpr double kGiantFactor = 4.0;

}  // namespace

void DiscGrid::file(const std::vector<Ball>& balls, const DiscBounds& bounds) {
  const std::size_t n = balls.size();
  cell_.resize(n);
  giants_.clear();
  // The usual case (no giant) needs nothing more than the bounds: mean and largest
  // radius, centre bounds.
  double r_max = bounds.r_max;
  double lo_x = bounds.lo_x, hi_x = bounds.hi_x, lo_y = bounds.lo_y, hi_y = bounds.hi_y;
  double mean_r = bounds.sum_r / static_cast<double>(n);
  if (!(mean_r > 0.0) || !std::isfinite(mean_r)) mean_r = 1.0;
  const double giant_r = kGiantFactor * mean_r;
  const bool has_giants = !(r_max <= giant_r);
  if (has_giants) {
    // Set the giants aside; the cells and bounds come from the others.
    r_max = 0.0;
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      const Ball& b = balls[i];
      if (!(b.radius <= giant_r)) {
        cell_[i] = kGiant;
        giants_.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      cell_[i] = 0;
      r_max = std::max(r_max, b.radius);
      if (!any) {
        lo_x = hi_x = b.pos.x;
        lo_y = hi_y = b.pos.y;
        any = true;
      } else {
        lo_x = std::min(lo_x, b.pos.x); hi_x = std::max(hi_x, b.pos.x);
        lo_y = std::min(lo_y, b.pos.y); hi_y = std::max(hi_y, b.pos.y);
      }
    }
  }
  grid_ = GridLayout::fit(lo_x, hi_x, lo_y, hi_y, kCellDiameters * 2.0 * r_max, n);

  // Counting sort: start_[c + 1] counts cell c, then (prefix sum) marks its end; filing
  // from the last disc down moves it to the cell's beginning, discs in index order.
  // So cell c is [start_[c + 1], start_[c + 2]).
  const std::size_t ncells = grid_.cells();
  start_.assign(ncells + 2, 0);
  const GridLayout grid = grid_;
  std::uint32_t* count = start_.data() + 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (has_giants && cell_[i] == kGiant) continue;
    const Ball& b = balls[i];
    const std::uint32_t c = grid.cell_of(b.pos.x, b.pos.y);
    cell_[i] = c;
    ++count[c];
  }
  for (std::size_t c = 1; c <= ncells; ++c) start_[c] += start_[c - 1];
  const std::uint32_t filed = start_[ncells];
  start_[ncells + 1] = filed;
  slots_.resize(filed);
  Slot* slots = slots_.data();
  for (std::size_t i = n; i-- > 0;) {
    const std::uint32_t c = cell_[i];
    if (has_giants && c == kGiant) continue;
    const Ball& b = balls[i];
    slots[--count[c]] = {b.pos.x, b.pos.y, b.radius, static_cast<std::uint32_t>(i)};
  }
}

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
  const Slot* slots = slots_.data();
  const std::uint32_t* begin = start_.data() + 1;  // cell c is [begin[c], begin[c + 1])
  for_each_stencil_slot(grid_, begin, [&](std::uint32_t p, const HalfStencil& st) {
    const Slot a = slots[p];
    auto test = [&](std::uint32_t q) {
      const double dx = slots[q].x - a.x, dy = slots[q].y - a.y, reach = a.r + slots[q].r;
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(std::min(a.id, slots[q].id), std::max(a.id, slots[q].id));
    };
    for (std::uint32_t q = p + 1; q < st.right_end; ++q) test(q);
    for (std::uint32_t q = st.up0; q < st.up1; ++q) test(q);
  });
  // Giants meet everything: filed discs, then later giants.
  for (std::size_t g = 0; g < giants_.size(); ++g) {
    const std::uint32_t gi = giants_[g];
    const Ball& a = balls[gi];
    for (const Slot& s : slots_) {
      const double dx = s.x - a.pos.x, dy = s.y - a.pos.y, reach = a.radius + s.r;
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(std::min(gi, s.id), std::max(gi, s.id));
    }
    for (std::size_t h = g + 1; h < giants_.size(); ++h) {
      const Ball& b = balls[giants_[h]];
      const double dx = b.pos.x - a.pos.x, dy = b.pos.y - a.pos.y, reach = a.radius + b.radius;
      if (dx * dx + dy * dy <= reach * reach) out.emplace_back(gi, giants_[h]);
    }
  }
}

}  // namespace fts::sim
