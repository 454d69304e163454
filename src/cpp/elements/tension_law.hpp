// A tabulated tension law T(e) of a stretch or strain e: a C1 piecewise cubic on breakpoints
// e_0 < ... < e_k, continued linearly with its end slopes beyond e_0 and e_k, with its slope
// T'(e) and its energy, the integral of T from 0 (exact for the cubic pieces).  One
// implementation for the springs' laws (system/spring_law.hpp: e the stretch [m]) and the
// nonlinear axial law of cables and rods (e the engineering strain; docs/derivations/axial-law.md).
#pragma once

namespace rancf {

/// A piecewise cubic as views: breaks (pieces + 1), coef (pieces, 4) with T = c0 + c1 s + c2 s^2
/// + c3 s^3, s = e - e_i (a time function's table layout, one component); pieces = 0: none.
struct TensionTable {
  const double* breaks = nullptr;
  const double* coef = nullptr;
  int pieces = 0;
  [[nodiscard]] bool active() const { return pieces > 0; }
};

/// T(e) and dT/de.
struct LawValue {
  double t, dt;
};

/// The law's tension and its slope at e.
LawValue tension_law(const TensionTable& law, double e);

/// The law's energy: the integral of T from 0 to e.
double tension_law_energy(const TensionTable& law, double e);

/// The axial energy density of the law per reference length and its derivatives in the
/// Green-Lagrange strain g (docs/derivations/axial-law.md eq. 3): with lambda = sqrt(1 + 2 g)
/// and the engineering strain e = lambda - 1, w = int_0^e T, dw = dw/dg = T / lambda and
/// ddw = d2w/dg2 = (T' lambda - T) / lambda^3.
struct AxialDensity {
  double w, dw, ddw;
};

AxialDensity axial_law_density(const TensionTable& law, double g);

}  // namespace rancf
