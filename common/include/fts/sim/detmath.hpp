// Deterministic replacements for libm transcendental functions, built only from
// + - * / and sqrt (all correctly rounded in IEEE 754), so results are bit-identical
// on every machine. Used where the game needs a power, e.g. friction 0.991^(100*dt).
#pragma once

namespace fts::sim {

// Natural logarithm for x > 0 (argument reduction by powers of two, then atanh series).
double det_log(double x);
// e^x for |x| < 700 (argument reduction by ln 2, then Taylor series).
double det_exp(double x);
// base^exponent for base > 0.
double det_pow(double base, double exponent);

}  // namespace fts::sim
