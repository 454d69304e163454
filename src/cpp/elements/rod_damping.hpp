// rod_damping.hpp -- Kelvin-Voigt strain-rate damping of the rod (docs/derivations/
// strain-rate-damping.md sections 2 and 3): N = EA eps + c_a deps/dt, twist moment GJ (K1 - K1^0)
// + c_t dK1/dt, bending moments EI (K_i - K_i^0) + c_b dK_i/dt (i = 2, 3). Each strain measure m
// of each quadrature point is the rod kernel's own (qterms with a unit coefficient on m), mapped
// to the element by the elastic force's chain (element_chain): its gradient G = dm/de and Hessian
// dG/de; then kv_measure (strain_rate.hpp): m' = G . ed (eq. 2), the force c m' G (eq. 3) and the
// Jacobians c G G^T (eq. 4) and c (G (dG/de ed)^T + m' dG/de) (eq. 5). Part of the rod kernel
// (included by rod.cpp).
#ifndef RANCF_ROD_DAMPING_HPP
#define RANCF_ROD_DAMPING_HPP

#include <algorithm>

#include "elements/rod_common.hpp"
#include "elements/rod_density.hpp"
#include "elements/rod_element.hpp"
#include "elements/strain_rate.hpp"

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

}  // namespace detail

// Damping force fe[14] at (e, ed = de/dt) and, if ke != nullptr, its Jacobian ke[14*14] = ck
// dfe/de + cv dfe/ded (not symmetric). NaN where the elastic kernel is (kMinAlign).
inline void damping(const ElementInput& in, const DampingCoef& c, const double* e, const double* ed,
                    double ck, double cv, double* fe, double* ke) {
  std::fill(fe, fe + 14, 0.0);
  const double cm[4] = {c.axial, c.torsion, c.bending, c.bending};
  double G[14], Hm[14][14], J[14][14] = {};
  for (int q = 0; q < in.nq; ++q)
    for (int m = 0; m < 4; ++m) {
      if (!(cm[m] > 0.0)) continue;
      const bool ok = ke != nullptr ? detail::measure_derivs<true>(in, e, q, m, G, &Hm[0][0])
                                    : detail::measure_derivs<false>(in, e, q, m, G, nullptr);
      if (!ok) {
        detail::fill_nan(fe, 14);
        if (ke != nullptr) detail::fill_nan(ke, 196);
        return;
      }
      kv_measure<14>(cm[m] * in.gw[q] * in.j0[q], G, Hm, ed, ck, cv, fe,
                     ke != nullptr ? J : nullptr);
    }
  if (ke != nullptr) std::copy(&J[0][0], &J[0][0] + 196, ke);
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_DAMPING_HPP
