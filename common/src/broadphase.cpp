#include "fts/sim/broadphase.hpp"

#include <algorithm>
#include <cmath>

#include "lanes.hpp"

namespace fts::sim {

// Cells as wide as the widest box (the least that keeps the stencil complete). With the
// half stencil over contiguous ranges, empty cells cost little, so smaller cells win:
// callgrind on continuous gas-10000, 10 ticks, scale 1 / 1.5 / 2 / 3: 52 / 53 / 58 /
// 75 M instructions, 306 / 320 / 352 / 394 k mispredicted branches.
constexpr double kCellScale = 1.0;
// A box wider than this many typical (mean) extents goes to the overflow list.
constexpr double kOverflowFactor = 4.0;
// The pair scan's fixed windows (see overlapping_pairs): the rest of a box's cell and
// the next one hold about 1.6 boxes, the three cells above about 3.3 (a gas at packing
// 0.2, cells one box wide). Build alone on gas-10000, best of 30, ns per ball, by
// (right, up) window: (4, 8) 37, (2, 4) 27, (1, 4) 25.5, (1, 5) 27, (1, 3) 28,
// (1, 2) 28-29, (3, 4) 29; gas-100000: 49-56 for all but (4, 8), 59-63. Wider windows
// test more empty slots, narrower ones need a second window more often. The slots are
// padded by the wider one.
constexpr std::uint32_t kRightWindow = 1;
constexpr std::uint32_t kUpWindow = 4;

void Grid::build() {
  const BigVector<Box>& boxes = boxes_;
  const std::size_t n = boxes.size();
  overflow_.clear();
  if (n == 0) {
    grid_ = GridLayout{};
    start_.assign(3, 0);
    slots_.clear();
    return;
  }
  // One pass for the usual case (no overflow): mean and widest extent, centre bounds.
  // The mean, so that a few giants barely move the typical extent.
  double sum = 0.0, widest = 0.0;
  double lo_x = 0.5 * (boxes[0].x0 + boxes[0].x1), hi_x = lo_x;
  double lo_y = 0.5 * (boxes[0].y0 + boxes[0].y1), hi_y = lo_y;
  for (const Box& b : boxes) {
    const double extent = std::max(b.x1 - b.x0, b.y1 - b.y0);
    sum += extent;
    widest = std::max(widest, extent);
    const double x = 0.5 * (b.x0 + b.x1), y = 0.5 * (b.y0 + b.y1);
    lo_x = std::min(lo_x, x); hi_x = std::max(hi_x, x);
    lo_y = std::min(lo_y, y); hi_y = std::max(hi_y, y);
  }
  double typical = sum / static_cast<double>(n);
  if (!(typical > 0.0) || !std::isfinite(typical)) typical = 1.0;
  const double overflow_extent = kOverflowFactor * typical;
  home_.resize(n);
  if (!(widest <= overflow_extent)) {
    // Set the overflow aside; the cells and bounds come from the others.
    overflow_flag_.assign(n, 0);
    widest = 0.0;
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      const Box& b = boxes[i];
      const double extent = std::max(b.x1 - b.x0, b.y1 - b.y0);
      if (!(extent <= overflow_extent)) {
        overflow_flag_[i] = 1;
        overflow_.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      widest = std::max(widest, extent);
      const double x = 0.5 * (b.x0 + b.x1), y = 0.5 * (b.y0 + b.y1);
      if (!any) {
        lo_x = hi_x = x;
        lo_y = hi_y = y;
        any = true;
      } else {
        lo_x = std::min(lo_x, x); hi_x = std::max(hi_x, x);
        lo_y = std::min(lo_y, y); hi_y = std::max(hi_y, y);
      }
    }
  }
  grid_ = GridLayout::fit(lo_x, hi_x, lo_y, hi_y, widest * kCellScale, n);

  // Counting sort: start_[c + 1] counts cell c, then (prefix sum) marks its end; filing
  // from the last box down moves it to the cell's beginning, boxes in index order.
  const std::size_t ncells = grid_.cells();
  start_.assign(ncells + 2, 0);
  std::uint32_t* count = start_.data() + 1;
  const bool overflow = !overflow_.empty();
  for (std::size_t i = 0; i < n; ++i) {
    if (overflow && overflow_flag_[i]) continue;
    const Box& b = boxes[i];
    const std::uint32_t c = grid_.cell_of(0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1));
    home_[i] = c;
    ++count[c];
  }
  for (std::size_t c = 1; c <= ncells; ++c) start_[c] += start_[c - 1];
  const std::uint32_t filed = start_[ncells];
  start_[ncells + 1] = filed;
  slots_.resize(filed + kUpWindow);  // a window may read past the last filed slot
  for (std::size_t i = n; i-- > 0;) {
    if (overflow && overflow_flag_[i]) continue;
    slots_[--count[home_[i]]] = {boxes[i], static_cast<std::uint32_t>(i)};
  }
}

void Grid::overlapping_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out) { scan_pairs<false>(out); }

void Grid::overlapping_disc_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out) {
  scan_pairs<true>(out);
}

template <bool kDiscs>
void Grid::scan_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out) {
  // Each slot is tested against two contiguous ranges: the rest of its cell and the
  // next one in its row, then the three cells of the row above. Their lengths vary from
  // slot to slot and about one candidate in three overlaps, so loops over the ranges
  // and branches on the tests mispredicted 3.9 times per slot (callgrind's branch
  // simulation). Instead each range is tested in fixed windows (the first always, more
  // only for a longer range), unrolled, the slots past its end masked off, the box test
  // on both axes at once, and every candidate is written out and kept by its bit. The
  // pair is written as found (ordering it here compiled to a branch that mispredicts).
  // For discs the test is on doubled centres and full widths, (sum_b - sum_a)^2 <=
  // (width_a + width_b)^2: no division, nothing but the two slots read.
  std::size_t count = 0;
  const std::uint32_t* begin = start_.data() + 1;  // cell c is [begin[c], begin[c + 1])
  for_each_stencil_slot(grid_, begin, [&](std::uint32_t p, const HalfStencil& st) {
    const std::uint32_t right = st.right_end - p - 1, up = st.up1 - st.up0;
    const std::size_t room = count + right + up + kRightWindow + kUpWindow;
    if (out.size() < room) out.resize(2 * room);
    auto* dst = out.data();
    const Slot* slots = slots_.data();
    const detail::D2 a_lo = detail::lanes(&slots[p].box.x0), a_hi = detail::lanes(&slots[p].box.x1);
    const detail::D2 a_sum = a_lo + a_hi;
    const double a_width = a_hi[0] - a_lo[0];
    const std::uint32_t i = slots[p].id;
    auto window = [&]<std::uint32_t kWidth>(std::uint32_t q, std::uint32_t end) {
      for (std::uint32_t w = 0; w < kWidth; ++w) {
        const Box& b = slots[q + w].box;
        const detail::D2 b_lo = detail::lanes(&b.x0), b_hi = detail::lanes(&b.x1);
        std::uint32_t hit;
        if constexpr (kDiscs) {
          const detail::D2 d = (b_lo + b_hi) - a_sum;
          const double reach = a_width + (b_hi[0] - b_lo[0]);
          const detail::D2 dd = d * d;
          hit = dd[0] + dd[1] <= reach * reach ? 1u : 0u;
        } else {
          // overlaps(): a.x0 <= b.x1 & a.y0 <= b.y1 & b.x0 <= a.x1 & b.y0 <= a.y1.
          const auto both = (a_lo <= b_hi) & (b_lo <= a_hi);
          hit = static_cast<std::uint32_t>(both[0] & both[1] & 1);
        }
        dst[count] = {i, slots[q + w].id};
        count += hit & static_cast<std::uint32_t>(q + w < end);
      }
    };
    window.template operator()<kRightWindow>(p + 1, st.right_end);
    for (std::uint32_t q = p + 1 + kRightWindow; q < st.right_end; q += kRightWindow)
      window.template operator()<kRightWindow>(q, st.right_end);
    window.template operator()<kUpWindow>(st.up0, st.up1);
    for (std::uint32_t q = st.up0 + kUpWindow; q < st.up1; q += kUpWindow)
      window.template operator()<kUpWindow>(q, st.up1);
  });
  out.resize(count);
  const std::uint32_t n = static_cast<std::uint32_t>(boxes_.size());
  for (std::uint32_t i : overflow_) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == i || (overflow_flag_[j] && j < i)) continue;
      if (overlaps(boxes_[i], boxes_[j])) out.emplace_back(i, j);
    }
  }
}

}  // namespace fts::sim
