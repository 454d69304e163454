// Tabulated spring laws (spring_law.hpp).
#include "system/spring_law.hpp"

#include <algorithm>
#include <cstddef>

namespace rancf {

namespace {

/// The piece of the stretch x (clamped to the breakpoints) and x's offset s in it.
std::size_t piece(const TimeFunction& f, double x, double& s) {
  const std::size_t k = f.breaks.size() - 1;
  const auto it = std::upper_bound(f.breaks.begin(), f.breaks.end(), x);
  std::size_t i = it == f.breaks.begin() ? 0 : static_cast<std::size_t>(it - f.breaks.begin()) - 1;
  i = std::min(i, k - 1);
  s = x - f.breaks[i];
  return i;
}

/// T, T' at x inside [t_0, t_k], and the integral of T over the piece from its start to x.
LawValue inside(const TimeFunction& f, double x, double* integral = nullptr) {
  double s = 0.0;
  const std::size_t i = piece(f, x, s);
  const double* c = f.coef.data() + 4 * i;
  if (integral != nullptr)
    *integral = s * (c[0] + s * (c[1] / 2.0 + s * (c[2] / 3.0 + s * c[3] / 4.0)));
  return {c[0] + s * (c[1] + s * (c[2] + s * c[3])), c[1] + s * (2.0 * c[2] + 3.0 * s * c[3])};
}

/// The integral of T from t_0 to x (any x: the linear continuations beyond the ends).
double primitive(const TimeFunction& f, double x) {
  const double lo = f.breaks.front(), hi = f.breaks.back();
  if (x < lo) {
    const LawValue v = inside(f, lo);
    const double d = x - lo;
    return d * (v.t + 0.5 * v.dt * d);
  }
  const double xc = std::min(x, hi);
  double s = 0.0, part = 0.0, sum = 0.0;
  const std::size_t i = piece(f, xc, s);
  for (std::size_t j = 0; j < i; ++j) {
    const double h = f.breaks[j + 1] - f.breaks[j];
    const double* c = f.coef.data() + 4 * j;
    sum += h * (c[0] + h * (c[1] / 2.0 + h * (c[2] / 3.0 + h * c[3] / 4.0)));
  }
  const LawValue v = inside(f, xc, &part);
  const double d = x - xc;  // beyond the last breakpoint
  return sum + part + d * (v.t + 0.5 * v.dt * d);
}

}  // namespace

LawValue spring_law(const TimeFunction& law, double e) {
  const double lo = law.breaks.front(), hi = law.breaks.back();
  const double x = std::min(std::max(e, lo), hi);
  const LawValue v = inside(law, x);
  return {v.t + v.dt * (e - x), v.dt};
}

double spring_law_energy(const TimeFunction& law, double e) {
  return primitive(law, e) - primitive(law, 0.0);
}

}  // namespace rancf
