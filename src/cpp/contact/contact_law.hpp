// The penalty law of contact (contact.hpp): pressure, slope, potential and means over gaps.
#pragma once

#include <algorithm>
#include <cmath>

namespace rancf {

/// The penalty law (contact.hpp): pressure p(g), its slope dp/dg and potential Phi(g) with
/// p = -dPhi/dg, for stiffness k and onset depth d:
///   g >= 0       p = 0
///   -d <= g < 0  p = k g^2 / (2 d)
///   g < -d       p = k (-g - d/2)
struct Penalty {
  double k = 0.0, d = 0.0;
  [[nodiscard]] double p(double g) const {
    if (g >= 0.0) return 0.0;
    if (g >= -d) return k * g * g / (2.0 * d);
    return k * (-g - 0.5 * d);
  }
  [[nodiscard]] double slope(double g) const {
    if (g >= 0.0) return 0.0;
    if (g >= -d) return k * g / d;
    return -k;
  }
  [[nodiscard]] double potential(double g) const {
    if (g >= 0.0) return 0.0;
    if (g >= -d) return -k * g * g * g / (6.0 * d);
    return k * (d * d / 6.0 + 0.5 * g * g + 0.5 * d * g);
  }
  /// Which piece g is in (0: below the onset, 1: onset, 2: free).
  [[nodiscard]] int piece(double g) const { return g < -d ? 0 : (g < 0.0 ? 1 : 2); }
  /// The integral of p over [a, b] (a < b) divided by (b - a), piece by piece (exact, no
  /// cancellation).
  [[nodiscard]] double mean(double a, double b) const {
    double sum = 0.0;
    if (a < -d) {
      const double hi = std::min(b, -d);
      sum += (hi - a) * k * (-0.5 * (a + hi) - 0.5 * d);
    }
    const double lo = std::max(a, -d), hi = std::min(b, 0.0);
    if (lo < hi) sum += (hi - lo) * k * (lo * lo + lo * hi + hi * hi) / (6.0 * d);
    return sum / (b - a);
  }
};

/// The mean of p over [ga, g1] and its derivatives with respect to both ends: closed forms
/// within one piece; across pieces (p is C1) the integral, or the midpoint's value and half its
/// slope where the interval is too short for the difference quotients.
inline void mean_pressure(const Penalty& law, double ga, double g1, double& p, double& dpa,
                          double& dp1) {
  const int c0 = law.piece(ga), c1 = law.piece(g1);
  const double k = law.k, d = law.d;
  if (c0 == c1) {
    switch (c0) {
      case 0:
        p = k * (-0.5 * (ga + g1) - 0.5 * d);
        dpa = dp1 = -0.5 * k;
        return;
      case 1:
        p = k * (ga * ga + ga * g1 + g1 * g1) / (6.0 * d);
        dpa = k * (2.0 * ga + g1) / (6.0 * d);
        dp1 = k * (ga + 2.0 * g1) / (6.0 * d);
        return;
      default:
        p = dpa = dp1 = 0.0;
        return;
    }
  }
  const double dg = g1 - ga;
  if (std::abs(dg) < 1e-9 * (d + std::abs(ga) + std::abs(g1))) {
    const double gm = 0.5 * (ga + g1);
    p = law.p(gm);
    dpa = dp1 = 0.5 * law.slope(gm);
    return;
  }
  p = dg > 0.0 ? law.mean(ga, g1) : law.mean(g1, ga);
  dp1 = (law.p(g1) - p) / dg;
  dpa = (p - law.p(ga)) / dg;
}

}  // namespace rancf
