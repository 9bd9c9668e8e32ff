#include "fts/sim/collide.hpp"

#include <cmath>
#include <limits>

namespace fts::sim {

void respond_seed(Ball& b1, Ball& b2) {
  // Contact angle phi: the direction from b1's centre to b2's (the rotated x axis).
  const double phi = std::atan2(b2.pos.y - b1.pos.y, b2.pos.x - b1.pos.x);
  const double v1 = std::hypot(b1.vel.x, b1.vel.y);
  const double v2 = std::hypot(b2.vel.x, b2.vel.y);
  const double th1 = std::atan2(b1.vel.y, b1.vel.x);
  const double th2 = std::atan2(b2.vel.y, b2.vel.x);
  const double m1 = b1.mass, m2 = b2.mass;
  const double v1xr = v1 * std::cos(th1 - phi);
  const double v1yr = v1 * std::sin(th1 - phi);
  const double v2xr = v2 * std::cos(th2 - phi);
  const double v2yr = v2 * std::sin(th2 - phi);
  double v1xrf = (v1xr * (m1 - m2) + 2.0 * m2 * v2xr) / (m1 + m2);
  double v2xrf = (v2xr * (m2 - m1) + 2.0 * m1 * v1xr) / (m1 + m2);
  if (std::isinf(m1) || std::isinf(m2)) {  // inf / inf above: the limits instead
    if (std::isinf(m1) && std::isinf(m2)) return;
    if (std::isinf(m1)) {
      v1xrf = v1xr;
      v2xrf = 2.0 * v1xr - v2xr;
    } else {
      v2xrf = v2xr;
      v1xrf = 2.0 * v2xr - v1xr;
    }
  }
  const double half_pi = 1.57079632679489661923;
  b1.vel = {v1xrf * std::cos(phi) + v1yr * std::cos(phi + half_pi),
            v1xrf * std::sin(phi) + v1yr * std::sin(phi + half_pi)};
  b2.vel = {v2xrf * std::cos(phi) + v2yr * std::cos(phi + half_pi),
            v2xrf * std::sin(phi) + v2yr * std::sin(phi + half_pi)};
}

int push_apart_seed(Ball& b1, const Ball& b2, int max_iterations) {
  const double reach = b1.radius + b2.radius;
  int steps = 0;
  while (length_sq(b1.pos - b2.pos) <= reach * reach) {
    if (steps == max_iterations) {
      // Guard: finish in one jump along the same axis signs instead of looping on.
      const Vec2 d = b1.pos - b2.pos;
      const double dist = length(d);
      const Vec2 n = dist > 0.0 ? d * (1.0 / dist) : Vec2{1.0, 0.0};
      b1.pos = b2.pos + n * (reach * (1.0 + 1e-12) + 1e-9);
      break;
    }
    const double dx = b1.pos.x - b2.pos.x;
    const double dy = b1.pos.y - b2.pos.y;
    if (dx == 0.0 && dy == 0.0) {
      b1.pos.x += 1.0;  // the seed divides by zero here; we pick +x deterministically
    } else {
      if (dx != 0.0) b1.pos.x += dx > 0.0 ? 1.0 : -1.0;
      if (dy != 0.0) b1.pos.y += dy > 0.0 ? 1.0 : -1.0;
    }
    ++steps;
  }
  return steps;
}

Vec2 unit_normal(Vec2 d, double dist) {
  if (dist > 0.0 && std::isfinite(1.0 / dist)) return d * (1.0 / dist);
  return {1.0, 0.0};
}

Vec2 contact_direction(Vec2 pa, Vec2 pb) {
  const Vec2 d = pb - pa;
  const double dd = length_sq(d);
  // A normal square (not subnormal, not infinite) has a finite reciprocal.
  if (dd >= std::numeric_limits<double>::min() && dd <= std::numeric_limits<double>::max()) return d;
  return contact_normal(pa, pb);
}

void separate(Ball& a, Ball& b, Vec2 n, double overlap) {
  if (!(overlap > 0.0)) return;
  const double wa = 1.0 / (1.0 + a.mass / b.mass);  // a's share: m_b / (m_a + m_b)
  const double wb = 1.0 / (1.0 + b.mass / a.mass);
  if (std::isnan(wa)) return;  // inf / inf: both immovable
  a.pos -= n * (overlap * wa);
  b.pos += n * (overlap * wb);
}

}  // namespace fts::sim
