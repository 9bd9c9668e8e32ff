// quantize(): a snapshot as it arrives at a client (the wire's resolution and ranges).
#include <algorithm>
#include <cmath>

#include "fts/protocol/constants.hpp"
#include "fts/protocol/snapshot.hpp"
#include "fts/sim/items.hpp"

namespace fts::protocol {

int shop_index(char item) {
  const auto it = sim::item_by_key(item);
  return it ? static_cast<int>(sim::index_of(*it)) : -1;
}

namespace {

std::int64_t q(double v) {
  if (!std::isfinite(v)) return 0;
  const double scaled = std::round(v * kQuantaPerUnit);
  const double lim = static_cast<double>(kMaxQuantized);
  return static_cast<std::int64_t>(std::clamp(scaled, -lim, lim));
}
double unq(std::int64_t v) { return static_cast<double>(v) / kQuantaPerUnit; }
double clean(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

Snapshot quantize(Snapshot s) {
  for (auto& b : s.balls) {
    b.x = unq(q(b.x));
    b.y = unq(q(b.y));
    b.vx = unq(q(b.vx));
    b.vy = unq(q(b.vy));
    b.radius = unq(std::max<std::int64_t>(0, q(b.radius)));
    b.mass = unq(std::max<std::int64_t>(0, q(b.mass)));
  }
  for (auto& p : s.players) {
    p.mass = std::clamp(clean(p.mass), 0.0, 1e15);
    p.vmax_u_per_s = std::clamp(clean(p.vmax_u_per_s), 0.0, 1e15);
    p.accel_u_per_s2 = std::clamp(clean(p.accel_u_per_s2), 0.0, 1e15);
    p.multiplier = std::clamp(clean(p.multiplier), 0.0, 1e15);
    p.coins = std::clamp<std::int64_t>(p.coins, 0, kMaxCoins);
    for (auto& price : p.prices) price = std::clamp<std::int64_t>(price, 0, kMaxCoins);
    p.lives = std::clamp(p.lives, 0, 1'000'000);
    if (p.name.size() > kMaxNameBytes) p.name.resize(kMaxNameBytes);
    for (char& c : p.name)
      if (c < 0x20 || c > 0x7E) c = '?';
    if (p.name.empty()) p.name.push_back('?');
  }
  std::sort(s.balls.begin(), s.balls.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::sort(s.players.begin(), s.players.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return s;
}

}  // namespace fts::protocol
