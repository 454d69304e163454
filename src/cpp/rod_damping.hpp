// rod_damping.hpp -- Kelvin-Voigt strain-rate damping of the rod (docs/derivations/
// strain-rate-damping.md sections 2 and 3): N = EA eps + c_a deps/dt, twist moment GJ (K1 - K1^0)
// + c_t dK1/dt, bending moments EI (K_i - K_i^0) + c_b dK_i/dt (i = 2, 3). Each strain measure m
// of each quadrature point is the rod kernel's own (qterms with a unit coefficient on m), mapped
// to the element by the elastic force's chain (element_chain): its gradient G = dm/de and Hessian
// dG/de; then m' = G . ed (eq. 2), the force c m' G (eq. 3) and the Jacobians c G G^T (eq. 4) and
// c (G (dG/de ed)^T + m' dG/de) (eq. 5). Part of the rod kernel (included by rod.cpp).
#ifndef RANCF_ROD_DAMPING_HPP
#define RANCF_ROD_DAMPING_HPP

#include <algorithm>

#include "rod_common.hpp"
#include "rod_density.hpp"
#include "rod_element.hpp"

namespace rancf::rod {

/// Damping coefficients: axial c_a (eps) [N s], torsion c_t (K1) and bending c_b (K2, K3)
/// [N m^2 s].
struct DampingCoef {
  double axial, torsion, bending;
};

namespace detail {

// Strain measure `measure` (0: eps, 1: K1, 2: K2, 3: K3) of quadrature point q0 as a function of
// the element coordinates: its gradient G[14] and, if WithH, Hessian Hm[14 * 14].
template <bool WithH>
inline bool measure_derivs(const ElementInput& in, const double* e, int q0, int measure, double* G,
                           double* Hm) {
  const auto unit = [measure](double, const double*) {
    Coef c{};
    double* slot[4] = {&c.cE, &c.c1, &c.c2, &c.c3};
    *slot[measure] = 1.0;
    return c;
  };
  const auto one = [&](int q, const double* a, const double* b, double aB, double th, double xq,
                       double* g, double (*H)[8]) {
    if (q == q0) return qterms<WithH>(a, b, aB, th, xq, in.j0[q], unit, g, H);
    std::fill(g, g + 8, 0.0);
    if (WithH)
      for (int i = 0; i < 8; ++i) std::fill(H[i], H[i] + 8, 0.0);
    return true;
  };
  return element_chain<WithH>(in, e, one, G, Hm);
}

// Adds the damping of one measure with coefficient k (times gw j0) into fe and, if ke, its
// Jacobian ck d/de + cv d/ded (eqs. 2-5).
inline void add_measure(double k, const double* G, const double* Hm, const double* ed, double ck,
                        double cv, double* fe, double* ke) {
  double md = 0.0, hv[14];
  for (int i = 0; i < 14; ++i) md += G[i] * ed[i];
  for (int i = 0; i < 14; ++i) fe[i] += k * md * G[i];
  if (ke == nullptr) return;
  for (int i = 0; i < 14; ++i) {
    hv[i] = 0.0;
    for (int j = 0; j < 14; ++j) hv[i] += Hm[i * 14 + j] * ed[j];
  }
  for (int i = 0; i < 14; ++i)
    for (int j = 0; j < 14; ++j)
      ke[i * 14 + j] += k * (ck * (G[i] * hv[j] + md * Hm[i * 14 + j]) + cv * G[i] * G[j]);
}

}  // namespace detail

// Damping force fe[14] at (e, ed = de/dt) and, if ke != nullptr, its Jacobian ke[14*14] = ck
// dfe/de + cv dfe/ded (not symmetric). NaN where the elastic kernel is (kMinAlign).
inline void damping(const ElementInput& in, const DampingCoef& c, const double* e, const double* ed,
                    double ck, double cv, double* fe, double* ke) {
  std::fill(fe, fe + 14, 0.0);
  if (ke != nullptr) std::fill(ke, ke + 196, 0.0);
  const double cm[4] = {c.axial, c.torsion, c.bending, c.bending};
  double G[14], Hm[196];
  for (int q = 0; q < in.nq; ++q)
    for (int m = 0; m < 4; ++m) {
      if (!(cm[m] > 0.0)) continue;
      const bool ok = ke != nullptr ? detail::measure_derivs<true>(in, e, q, m, G, Hm)
                                    : detail::measure_derivs<false>(in, e, q, m, G, nullptr);
      if (!ok) {
        detail::fill_nan(fe, 14);
        if (ke != nullptr) detail::fill_nan(ke, 196);
        return;
      }
      detail::add_measure(cm[m] * in.gw[q] * in.j0[q], G, Hm, ed, ck, cv, fe, ke);
    }
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_DAMPING_HPP
