// The continuous model's event queue (internal): events ordered by (time, a, b), so
// that equal times still pop in one defined order, in a binary heap the world owns.
#pragma once

#include <algorithm>
#include <vector>

#include "fts/sim/step_buffers.hpp"

namespace fts::sim::detail {

// b is another ball's index or kWallX / kWallY / kFall.
using Event = TimedEvent;
struct Later {
  bool operator()(const Event& x, const Event& y) const {
    if (x.t != y.t) return x.t > y.t;
    if (x.a != y.a) return x.a > y.a;
    return x.b > y.b;
  }
};

// The event queue: a binary heap (earliest first) in a vector the world owns.
class EventHeap {
 public:
  explicit EventHeap(std::vector<Event>& storage) : v_(storage) { v_.clear(); }
  bool empty() const { return v_.empty(); }
  const Event& top() const { return v_.front(); }
  void push(const Event& e) {
    v_.push_back(e);
    std::push_heap(v_.begin(), v_.end(), Later{});
  }
  void pop() {
    std::pop_heap(v_.begin(), v_.end(), Later{});
    v_.pop_back();
  }
  void clear() { v_.clear(); }

 private:
  std::vector<Event>& v_;
};

}  // namespace fts::sim::detail
