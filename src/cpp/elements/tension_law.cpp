// Tabulated tension laws (tension_law.hpp).
#include "elements/tension_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rancf {

namespace {

/// The piece of x (clamped to the breakpoints) and x's offset s in it.
std::size_t piece(const TensionTable& f, double x, double& s) {
  const auto k = static_cast<std::size_t>(f.pieces);
  const double* end = f.breaks + k + 1;
  const double* it = std::upper_bound(f.breaks, end, x);
  std::size_t i = it == f.breaks ? 0 : static_cast<std::size_t>(it - f.breaks) - 1;
  i = std::min(i, k - 1);
  s = x - f.breaks[i];
  return i;
}

/// T, T' at x inside [e_0, e_k], and the integral of T over the piece from its start to x.
LawValue inside(const TensionTable& f, double x, double* integral = nullptr) {
  double s = 0.0;
  const std::size_t i = piece(f, x, s);
  const double* c = f.coef + 4 * i;
  if (integral != nullptr)
    *integral = s * (c[0] + s * (c[1] / 2.0 + s * (c[2] / 3.0 + s * c[3] / 4.0)));
  return {c[0] + s * (c[1] + s * (c[2] + s * c[3])), c[1] + s * (2.0 * c[2] + 3.0 * s * c[3])};
}

/// The integral of T from e_0 to x (any x: the linear continuations beyond the ends).
double primitive(const TensionTable& f, double x) {
  const double lo = f.breaks[0], hi = f.breaks[f.pieces];
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
    const double* c = f.coef + 4 * j;
    sum += h * (c[0] + h * (c[1] / 2.0 + h * (c[2] / 3.0 + h * c[3] / 4.0)));
  }
  const LawValue v = inside(f, xc, &part);
  const double d = x - xc;  // beyond the last breakpoint
  return sum + part + d * (v.t + 0.5 * v.dt * d);
}

}  // namespace

LawValue tension_law(const TensionTable& law, double e) {
  const double lo = law.breaks[0], hi = law.breaks[law.pieces];
  const double x = std::min(std::max(e, lo), hi);
  const LawValue v = inside(law, x);
  return {v.t + v.dt * (e - x), v.dt};
}

double tension_law_energy(const TensionTable& law, double e) {
  return primitive(law, e) - primitive(law, 0.0);
}

AxialDensity axial_law_density(const TensionTable& law, double g) {
  const double lam = std::sqrt(1.0 + 2.0 * g);
  const double e = 2.0 * g / (lam + 1.0);  // lambda - 1 without cancellation
  const LawValue v = tension_law(law, e);
  return {tension_law_energy(law, e), v.t / lam, (v.dt * lam - v.t) / (lam * lam * lam)};
}

}  // namespace rancf
