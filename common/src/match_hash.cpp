// The match's state hash: every field that influences a future tick, in id order.
#include "fts/sim/hash.hpp"
#include "fts/sim/match.hpp"

namespace fts::sim {
namespace {

// Whole-coin prices are written as integers with the other counts, fractional prices as
// doubles after the speeds (the order the hash has always had).
void add_economy(Hasher& h, const Economy& e) {
  for (Coins c : {e.coins, e.lives, e.mass}) h.add_i64(c);
  for (const ItemDef& d : item_table())
    if (d.whole_price) h.add_i64(static_cast<Coins>(e.prices[d.item]));
  for (Coins c : {e.start_coins, e.earned_defeats, e.earned_interest, e.spent, e.purchases, e.defeats}) h.add_i64(c);
  for (double d : {e.vmax_u_per_s, e.accel_u_per_s2, e.multiplier}) h.add_double(d);
  for (const ItemDef& d : item_table())
    if (!d.whole_price) h.add_double(e.prices[d.item]);
  h.add_u64((e.bank ? 1u : 0u) | (e.rockets ? 2u : 0u));
}

}  // namespace

std::uint64_t match_hash(const MatchState& s) {
  Hasher h;
  h.add_u64(static_cast<std::uint64_t>(s.phase));
  for (std::int64_t v : {s.tick, s.level, s.levels_cleared, s.shop_deadline_tick, s.matches_started})
    h.add_i64(v);
  // Fields added later are mixed in only when set, so the hashes of matches that never
  // use them (every committed golden hash) stay what they were.
  if (s.lobby_deadline_tick >= 0) h.add_i64(s.lobby_deadline_tick);
  for (std::uint64_t w : s.rng.state()) h.add_u64(w);
  h.add_u64(s.next_ball_id);
  h.add_u64(s.players.size());
  for (const Player& p : s.players) {
    h.add_u64(p.id.value);
    h.add_string(p.name);
    add_economy(h, p.eco);
    h.add_u64(p.ready ? 1 : 0);
    h.add_u64(p.connected ? 1 : 0);
    if (p.parked) h.add_u64(0x9a4ced);
    h.add_u64(p.ball.value);
    h.add_i64(p.respawn_tick);
    if (p.protected_until_tick >= 0) {  // only when set (see above)
      h.add_u64(0x5a1e1d);
      h.add_i64(p.protected_until_tick);
    }
    h.add_i64(p.next_fire_tick);
    h.add_double(p.aim.x);
    h.add_double(p.aim.y);
  }
  h.add_u64(s.world.balls.size());
  for (const Ball& b : s.world.balls) {
    h.add_u64(b.id.value);
    for (double d : {b.pos.x, b.pos.y, b.vel.x, b.vel.y, b.radius, b.mass}) h.add_double(d);
  }
  h.add_u64(s.bodies.size());
  for (const auto& [id, b] : s.bodies) {
    h.add_u64(id.value);
    h.add_u64(static_cast<std::uint64_t>(b.kind));
    h.add_u64(b.owner.value);
    h.add_i64(b.index);
    for (double d : {b.spec.mass, b.spec.radius_u, b.spec.accel_u_per_s2, b.spec.vmax_u_per_s, b.goal.x, b.goal.y})
      h.add_double(d);
    h.add_u64(static_cast<std::uint64_t>(b.spec.role));
    h.add_u64(b.credit.value);
    h.add_i64(b.credit_tick);
    h.add_i64(b.expires_tick);
  }
  return h.value();
}

}  // namespace fts::sim
