// Pairwise collision response; shared by the models and tested against each other.
#pragma once

#include <cmath>

#include "fts/sim/ball.hpp"

namespace fts::sim {

// The seed's rotated-axes formulas (atan2/cos/sin), applied unconditionally; for an
// immovable ball (mass +inf) their limit M1 >> M2 (two immovable balls: nothing).
void respond_seed(Ball& b1, Ball& b2);
// The seed's push-apart: b1 moves one unit per axis away from b2 until they no longer
// overlap. A zero difference on an axis moves nothing on it; both zero moves b1 along +x.
// Bounded: after max_iterations any remaining overlap is removed in one jump.
// Returns the number of unit steps taken.
int push_apart_seed(Ball& b1, const Ball& b2, int max_iterations = 4096);

// d / dist for d of length dist (a caller that has the length already); a fixed
// deterministic +x where that is no usable unit vector (dist zero, NaN or tiny).
Vec2 unit_normal(Vec2 d, double dist);
// Unit contact normal from a centre at pa to one at pb; for coincident centres a fixed
// deterministic +x.
inline Vec2 contact_normal(Vec2 pa, Vec2 pb) { return unit_normal(pb - pa, length(pb - pa)); }
inline Vec2 contact_normal(const Ball& a, const Ball& b) { return contact_normal(a.pos, b.pos); }
// The direction from a's centre to b's for respond_elastic: the centres' difference
// itself, or contact_normal where its square is not a usable divisor (coincident,
// underflowing or overflowing).
Vec2 contact_direction(Vec2 pa, Vec2 pb);
inline Vec2 contact_direction(const Ball& a, const Ball& b) { return contact_direction(a.pos, b.pos); }
// Elastic impulse along d (from a towards b, any length) if the pair approaches.
// Returns true when an impulse was applied. Written with d and its square rather than a
// unit normal: d / |d| comes out a few ulp off unit length, and at contact the error had
// one sign (|d| = r_a + r_b, the continuous model keeping balls a hair apart, and a
// power of two in the gas), so every collision added energy: gas-1000 gained 5.8e-9 of
// 50 000 per 10^4 ticks, linearly. With d in the numerator and its square in the
// denominator the rounding errors have no preferred sign (BENCHMARKS.md, issue 18).
// B is a Ball or the continuous model's working copy of one (anything with vel and mass).
// A ball of mass +inf is immovable (see Ball::mass): its share comes out 0 and the
// other's 2, a reflection off a fixed ball; two immovable balls do not act on each other.
template <class B>
bool respond_elastic(B& a, B& b, Vec2 d) {
  const double vd = dot(b.vel - a.vel, d);  // < 0: approaching
  if (!(vd < 0.0)) return false;
  const double f = vd / length_sq(d);  // the normal relative speed over |d|
  // Each ball's share, written so that mass ratios of 1e9 stay finite and exact-ish.
  const double wa = 2.0 / (1.0 + a.mass / b.mass);  // = 2 m_b / (m_a + m_b)
  const double wb = 2.0 / (1.0 + b.mass / a.mass);  // = 2 m_a / (m_a + m_b)
  if (std::isnan(wa)) return false;  // inf / inf: both immovable
  a.vel += d * (wa * f);
  b.vel -= d * (wb * f);
  return true;
}
// Removes the overlap along n, each ball moving in proportion to the other's mass (an
// immovable ball not at all; two immovable balls stay where they are).
void separate(Ball& a, Ball& b, Vec2 n, double overlap);

}  // namespace fts::sim
