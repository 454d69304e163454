// rod_common.hpp -- the rod kernel's inputs (stiffness, element data), its alignment threshold and
// the small vector helpers every part of it shares. Part of the rod kernel: see rod_kernel.hpp for
// the formulation and the order of the computation (docs/derivations/rod-kernel.md).
#ifndef RANCF_ROD_COMMON_HPP
#define RANCF_ROD_COMMON_HPP

#include <cmath>

#include "elements/tension_law.hpp"

namespace rancf::rod {

// axial_law: the tension T(e) of the engineering strain in place of EA (none: EA;
// docs/derivations/axial-law.md).
struct Stiffness {
  double ea, gj, ei2, ei3;
  TensionTable axial_law{};
};

// Node dofs: 7 per node = r(3), r_x(3), phi(1). Element vector e[14]: node A e[0..6], node B
// e[7..13]. n1[q*4+k], n2[q*4+k]: first/second xi-derivatives of the 4 cable shape-function blocks
// (k = 0: rA, 1: rA_x, 2: rB, 3: rB_x); xi[q] Gauss point in [0,1], gw[q] weight, j0[q] =
// |r0'(xi_q)|, kref[q*3+i] = reference material curvatures (K1^0, K2^0, K3^0). Nodal reference
// triads: unit, orthogonal.
struct ElementInput {
  const double* n1;
  const double* n2;
  const double* xi;
  const double* gw;
  const double* j0;
  const double* kref;
  int nq;
  const double* tref_a;
  const double* m1ref_a;
  const double* tref_b;
  const double* m1ref_b;
};

// Smallest admissible value of 1 + a.b in a smallest rotation SR(a -> b) (see rod_kernel.hpp).
constexpr double kMinAlign = 1e-8;

namespace detail {

inline double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline void cross3(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

inline double nan_value() { return std::nan(""); }

constexpr int kPosOff[4] = {0, 3, 7, 10};  // e offsets of the blocks rA, rA_x, rB, rB_x
constexpr int kAlphaDof[8] = {3, 4, 5, 6, 10, 11, 12, 13};  // e indices of (rA_x, phiA, rB_x, phiB)

// The axial energy density per reference length w(eps) of the Green-Lagrange strain eps and its
// first two derivatives: 1/2 EA eps^2, EA eps, EA; or the axial law's
// (docs/derivations/axial-law.md eq. 3).
inline AxialDensity axial_density(const Stiffness& s, double eps) {
  if (s.axial_law.active()) return axial_law_density(s.axial_law, eps);
  return {0.5 * s.ea * eps * eps, s.ea * eps, s.ea};
}

inline void fill_nan(double* p, int n) {
  for (int i = 0; i < n; ++i) p[i] = nan_value();
}

}  // namespace detail

}  // namespace rancf::rod

#endif  // RANCF_ROD_COMMON_HPP
