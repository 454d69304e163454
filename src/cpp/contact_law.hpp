// The penalty law of contact (contact.hpp): pressure, slope, potential and means over gaps.
#pragma once

#include <algorithm>

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

}  // namespace rancf
