// quantize(): a snapshot as it arrives at a client (the wire's resolution and ranges).
#include <algorithm>
#include <cmath>

#include "fts/protocol/constants.hpp"
#include "fts/protocol/snapshot.hpp"
#include "fts/sim/items.hpp"
#include "quanta.hpp"
#include "tables.hpp"

namespace fts::protocol {

int shop_index(char item) {
  const auto it = sim::item_by_key(item);
  return it ? static_cast<int>(sim::index_of(*it)) : -1;
}

using wire::from_quanta;
using wire::to_quanta;

Snapshot quantize(Snapshot s) {
  for (auto& b : s.balls) {
    b.x = from_quanta(to_quanta(b.x));
    b.y = from_quanta(to_quanta(b.y));
    b.vx = from_quanta(to_quanta(b.vx));
    b.vy = from_quanta(to_quanta(b.vy));
    b.radius = from_quanta(std::max<std::int64_t>(0, to_quanta(b.radius)));
    b.mass = from_quanta(std::max<std::int64_t>(0, to_quanta(b.mass)));
  }
  // Every player field into the range its table row states (tables.hpp).
  for (auto& p : s.players) wire::clamp_all(wire::kPlayerSynced, p);
  std::sort(s.balls.begin(), s.balls.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::sort(s.players.begin(), s.players.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return s;
}

}  // namespace fts::protocol
