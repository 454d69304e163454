// rod_kernel.hpp -- spatial Kirchhoff rod with torsion on a rational ANCF (RANCF) cable centerline.
//
// Formulation: docs/derivations/rod-kernel.md (smallest-rotation triads plus an interpolated
// relative twist, after Meier, Popp & Wall 2014, CMAME 278). Centerline interpolation:
// docs/derivations/cable.md sections 3 and 6. Derivation of every formula below, in the order of
// the code: docs/derivations/rod-kernel.md.
//
// Header-only, dependency-free C++17. Plain pointers, row-major matrices.
//
// Element coordinates e[14]: node A = e[0..6] = (rA, rA_x, phiA), node B = e[7..13] = (rB, rB_x,
// phiB).
//
// Structure of the computation (docs/derivations/rod-kernel.md section 0), all derivatives
// hand-derived:
//   * per element: node A's transported frame R0 = (tA, uA, vA), uA = SR(tref_A -> tA) m1ref_A, vA
//   = tA x uA,
//     with first derivatives with respect to rA_x and the few scalars that give its second
//     derivatives in contracted form; node B's triad (values); the relative twist alpha_B =
//     wrap(phiB - phiA + beta) where beta depends on the two tangents only, with a closed-form
//     gradient and 6x6 Hessian (twist vectors of smallest rotations); the four position blocks
//     rotated into R0: p~_k = R0^T p_k.
//   * per quadrature point: the energy density written in R0 depends only on (a~, b~, phiA,
//   alpha_B)
//     (a~, b~ = r', r'' in R0; the material triad is turned by theta = phiA + xi alpha_B about t);
//     its gradient and 8x8 Hessian are mapped by the 4 shape-function blocks exactly like the 3D
//     cable.
//   * per element again: the chain rule from (p~, phiA, alpha_B) back to e (R0 depends on rA_x
//   only).
//
// Singular configurations: the smallest rotation SR(a -> b) is undefined for a.b = -1. The kernel
// requires 1 + a.b > kMinAlign for (t_ref, t) at both nodes, (t_A, t_B) and (t_A, t(xi_q)) at every
// quadrature point. This holds whenever nodes are re-referenced after converged steps. Otherwise
// energy() returns NaN and curvatures()/forces() fill every output with NaN on purpose (so the
// caller's isfinite check on the residual rejects the step); min_alignment() returns the smallest
// of these quantities, so a caller can test before evaluating. A zero tangent (|r'| = 0 or |r_x| =
// 0) is outside the model, as for the cable.
//
// The kernel is split by stage; this header holds the public API and includes the rest:
//   rod_common.hpp   inputs, kMinAlign, vector helpers
//   rod_frames.hpp   nodal triads and the relative twist (derivation sections 1, 2)
//   rod_density.hpp  curvatures and energy density at a quadrature point (sections 3, 4)
//   rod_element.hpp  element force and tangent, chain rule (sections 0, 5)
//   rod_moments.hpp  point moments with their load stiffness (section 6)
// The rotary inertia (section 11) is in rod_inertia.hpp and rod_spin.hpp (included by rod.cpp).
#ifndef RANCF_ROD_KERNEL_HPP
#define RANCF_ROD_KERNEL_HPP

#include <algorithm>
#include <cmath>

#include "elements/rod_common.hpp"
#include "elements/rod_element.hpp"
#include "elements/rod_frames.hpp"
#include "elements/rod_moments.hpp"

namespace rancf::rod {

// ---------------------------------------------------------------------------------------------------------
// Public API

// Material curvatures K1, K2, K3 (out_k[q*3+i]) and Green-Lagrange axial strain (out_eps[q]) at
// every q.
inline void curvatures(const ElementInput& in, const double* e, double* out_k, double* out_eps) {
  detail::ElemValues v;
  detail::elem_values(in, e, v);
  bool ok = v.align > kMinAlign;
  double pt[4][3];
  detail::rotate_blocks(e, v.tA, v.uA, v.vA, pt);
  for (int q = 0; ok && q < in.nq; ++q) {
    double a[3], b[3], n2;
    detail::local_ab(in, q, pt, a, b);
    ok = detail::qcurv(a, b, v.alphaB, e[6] + in.xi[q] * v.alphaB, out_k + 3 * q, n2);
    const double j2 = in.j0[q] * in.j0[q];
    out_eps[q] = 0.5 * (n2 - j2) / j2;
  }
  if (!ok) {
    detail::fill_nan(out_k, 3 * in.nq);
    detail::fill_nan(out_eps, in.nq);
  }
}

// U = sum_q gw j0 [w(eps) + 1/2 (GJ (K1-K1^0)^2 + EI2 (K2-K2^0)^2 + EI3 (K3-K3^0)^2)], with
// w(eps) = 1/2 EA eps^2 or the axial law's (axial_density)
inline double energy(const ElementInput& in, const Stiffness& s, const double* e) {
  detail::ElemValues v;
  detail::elem_values(in, e, v);
  if (!(v.align > kMinAlign)) return detail::nan_value();
  double pt[4][3];
  detail::rotate_blocks(e, v.tA, v.uA, v.vA, pt);
  double U = 0.0;
  for (int q = 0; q < in.nq; ++q) {
    double a[3], b[3], K[3], n2;
    detail::local_ab(in, q, pt, a, b);
    if (!detail::qcurv(a, b, v.alphaB, e[6] + in.xi[q] * v.alphaB, K, n2))
      return detail::nan_value();
    const double j2 = in.j0[q] * in.j0[q];
    const double eps = 0.5 * (n2 - j2) / j2;
    const double* k0 = in.kref + 3 * q;
    const double r1 = K[0] - k0[0], r2 = K[1] - k0[1], r3 = K[2] - k0[2];
    U += in.gw[q] * in.j0[q] *
         (detail::axial_density(s, eps).w +
          0.5 * (s.gj * r1 * r1 + s.ei2 * r2 * r2 + s.ei3 * r3 * r3));
  }
  return U;
}

// fe[14] = dU/de and, if ke != nullptr, ke[14*14] = d2U/de2 (exact, symmetric).
inline void forces(const ElementInput& in, const Stiffness& s, const double* e, double* fe,
                   double* ke) {
  const bool ok = ke ? detail::element_forces<true>(in, s, e, fe, ke)
                     : detail::element_forces<false>(in, s, e, fe, nullptr);
  if (!ok) {
    detail::fill_nan(fe, 14);
    if (ke) detail::fill_nan(ke, 196);
  }
}

// Nodal triad for the current nodal gradient rx and twist phi (docs/derivations/rod.md 2).
inline void nodal_triad(const double* tref, const double* m1ref, const double* rx, double phi,
                        double* t_out, double* m1_out) {
  double u[3], v[3], m2[3];
  const double p = detail::triad_value(tref, m1ref, rx, phi, t_out, u, v, m1_out, m2);
  if (!(p > kMinAlign)) {
    detail::fill_nan(t_out, 3);
    detail::fill_nan(m1_out, 3);
  }
}

// Smallest 1 + a.b over the smallest rotations the element uses: (tref_A, tA), (tref_B, tB), (tA,
// tB) and (tA, t(xi_q)) for all q. The kernels return NaN when this is <= kMinAlign.
inline double min_alignment(const ElementInput& in, const double* e) {
  detail::ElemValues v;
  detail::elem_values(in, e, v);
  double amin = v.align;
  double pt[4][3];
  detail::rotate_blocks(e, v.tA, v.uA, v.vA, pt);
  for (int q = 0; q < in.nq; ++q) {
    double a[3], b[3];
    detail::local_ab(in, q, pt, a, b);
    amin = std::min(amin, 1.0 + a[0] / std::sqrt(detail::dot3(a, a)));
  }
  return amin;
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_KERNEL_HPP
