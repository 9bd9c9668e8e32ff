#include "fts/sim/detmath.hpp"

#include <cmath>
#include <limits>

namespace fts::sim {
namespace {
constexpr double kLn2 = 0.693147180559945309417232121458176568;
}

double det_log(double x) {
  if (!(x > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(x)) return x;
  // x = m * 2^e with m in [sqrt(1/2), sqrt(2)); frexp and ldexp are exact.
  int e = 0;
  double m = std::frexp(x, &e);  // m in [0.5, 1)
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    e -= 1;
  }
  // ln(m) = 2 atanh(s), s = (m-1)/(m+1), |s| < 0.1716: the series converges fast.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double term = s;
  double sum = 0.0;
  for (int k = 1; k < 60; k += 2) {
    sum += term / k;
    term *= s2;
    if (term == 0.0) break;
  }
  return 2.0 * sum + e * kLn2;
}

double det_exp(double x) {
  if (x > 709.0) return std::numeric_limits<double>::infinity();
  if (x < -745.0) return 0.0;
  // x = k ln2 + r with |r| <= ln2/2; e^x = 2^k e^r.
  const double k = std::nearbyint(x / kLn2);
  // Cody-Waite: ln 2 split in two so that k * hi is exact and r keeps full precision.
  constexpr double kLn2Hi = 6.93147180369123816490e-01;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double term = 1.0;
  double sum = 1.0;
  for (int n = 1; n < 40; ++n) {
    term *= r / n;
    sum += term;
    if (std::fabs(term) < 1e-18) break;
  }
  return std::ldexp(sum, static_cast<int>(k));
}

double det_pow(double base, double exponent) {
  if (exponent == 0.0) return 1.0;
  if (exponent == 1.0) return base;
  // Integer exponents by repeated squaring (exact sequence of products).
  if (std::nearbyint(exponent) == exponent && std::fabs(exponent) < 1e9) {
    long long n = static_cast<long long>(exponent);
    const bool neg = n < 0;
    if (neg) n = -n;
    double result = 1.0, b = base;
    while (n > 0) {
      if (n & 1) result *= b;
      b *= b;
      n >>= 1;
    }
    return neg ? 1.0 / result : result;
  }
  return det_exp(exponent * det_log(base));
}

}  // namespace fts::sim
