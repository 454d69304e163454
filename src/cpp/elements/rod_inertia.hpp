// rod_inertia.hpp -- the rod's rotary inertia (docs/derivations/rod-kernel.md section 11): the
// kinetic energy of the cross-sections' rotation with the exact spin s = omega . t of the material
// frame, the configuration-dependent mass matrix, the gyroscopic forces and their exact tangents.
// Part of the rod kernel (rod.cpp includes it beside rod_kernel.hpp).
//
// Spin at xi (11.2): nu_N is the spin of node N's smallest rotation from its reference tangent,
// sigma(1, 2) that of SR(t1 -> t2) about t2 (both linear in the velocities, c . xdot):
//   s(xi) = (1 - xi)(phidot_A + nu_A) + xi (phidot_B + nu_B) - xi sigma(A, B) + sigma(A, xi)
//   nu    = c . xdot,                  c  = (x x tr) / (|x| (|x| + tr . x))             (11.3)
//   sigma = c1 . xdot1 + c2 . xdot2,   ci = (x2 x x1) / (|xi| (|x1||x2| + x1 . x2))
// Kinetic energy (11.1), a = r'(xi), w = gw j0:
//   T = 1/2 sum_q w [rho_polar s^2 + rho_bend |P adot|^2 / |a|^2],  P = I - a a^T / |a|^2
// Inertial force F = d/dt dT/dedot - dT/de (11.4), per point:
//   w rho_polar [sdot G + s EL],  G = ds/dedot,  EL = -(a x adot) / |a|^3 on the a-slot
//   w rho_bend [P addot / |a|^2 - 2 (a . adot) P adot / |a|^4]     (on the a-slot)
// and mass-proportional damping c dT/dedot. The tangents (11.5) use G, the time derivatives of
// s, G and h = ds/de, and the second derivative dG/de; every piece is a small closed form of one or
// two vectors evaluated with a value-and-time-derivative number (Dual).
#ifndef RANCF_ROD_INERTIA_HPP
#define RANCF_ROD_INERTIA_HPP

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "elements/rod_common.hpp"
#include "elements/rod_spin.hpp"

namespace rancf::rod {

/// Rotary inertia per length: rho (I2 + I3) about the tangent, rho I about both bending axes
/// (zero: the "torsion" model).
struct InertiaCoef {
  double polar, bend;
};

/// Coefficients of the combined inertia tangent ck dF/de + cv dF/dedot + ca dF/deddot, and the
/// mass-proportional damping c (force c dT/dedot).
struct InertiaScales {
  double damping, ck, cv, ca;
};

namespace detail {

// 11-vector x on (xA, xB, a, phiA, phiB) -> 14 element coordinates (the map L^T, a = sum n1_k p_k).
inline void map_to_element(const double* x, const double* n1, double* out) {
  for (int i = 0; i < 14; ++i) out[i] = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 4; ++k) out[kPosOff[k] + i] += n1[k] * x[6 + i];
    out[3 + i] += x[i];
    out[10 + i] += x[3 + i];
  }
  out[6] += x[9];
  out[13] += x[10];
}

// d(P w / n^2)/da with P = I - a a^T / n^2 (bending inertia, 11.4).
inline void dq_da(const double* a, double n2, const double* w, const double* Qw, double (*D)[3]) {
  const double aw = dot3(a, w), in2 = 1.0 / n2;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      D[i][j] =
          (-(aw * (i == j ? 1.0 : 0.0) + a[i] * w[j]) * in2 + 2.0 * aw * a[i] * a[j] * in2 * in2) *
              in2 -
          2.0 * Qw[i] * a[j] * in2;
}

// Per-element spin pieces (11.2): the node spins nu_A, nu_B and the pair spin sigma(A, B) with
// their coefficients c and gradients h (T = Dual: with time derivatives) and dc/dx (values).
template <class T>
struct SpinPieces {
  T xA[3], vA[3], pA, pB;  // node A's gradient and its rate; twist rates
  T cA[3], cB[3], cAB[6], nuA, nuB, sAB, hA[3], hB[3], hAB[6];
  double DcA[3][3], DcB[3][3], DcAB[6][6];
};

// Element coordinates as T (value, or value and rate) at offset o: x = e + o, w = ed + o.
template <class T>
inline void lift3(const double* e, const double* ed, const double* edd, int o, T* x, T* w);
template <>
inline void lift3<double>(const double* e, const double* ed, const double*, int o, double* x,
                          double* w) {
  for (int i = 0; i < 3; ++i) {
    x[i] = e[o + i];
    w[i] = ed[o + i];
  }
}
template <>
inline void lift3<Dual>(const double* e, const double* ed, const double* edd, int o, Dual* x,
                        Dual* w) {
  for (int i = 0; i < 3; ++i) {
    x[i] = Dual(e[o + i], ed[o + i]);
    w[i] = Dual(ed[o + i], edd[o + i]);
  }
}
// Fills the pieces (gradients only WithH); false if a smallest rotation is singular.
template <class T, bool WithH>
inline bool spin_pieces(const ElementInput& in, const double* e, const double* ed,
                        const double* edd, SpinPieces<T>& P) {
  T xB[3], vB[3];
  lift3<T>(e, ed, edd, 3, P.xA, P.vA);
  lift3<T>(e, ed, edd, 10, xB, vB);
  const double* z = edd != nullptr ? edd : ed;  // unused for T = double
  P.pA = T(ed[6]);
  P.pB = T(ed[13]);
  if constexpr (std::is_same_v<T, Dual>) {
    P.pA = Dual(ed[6], z[6]);
    P.pB = Dual(ed[13], z[13]);
  }
  double al = node_spin(P.xA, P.vA, in.tref_a, P.cA, P.nuA, WithH ? P.hA : nullptr,
                        WithH ? P.DcA : nullptr);
  al = std::min(al, node_spin(xB, vB, in.tref_b, P.cB, P.nuB, WithH ? P.hB : nullptr,
                              WithH ? P.DcB : nullptr));
  al = std::min(al, pair_spin(P.xA, xB, P.vA, vB, P.cAB, P.sAB, WithH ? P.hAB : nullptr,
                              WithH ? P.DcAB : nullptr));
  return al > kMinAlign;
}

// Spin at point q (11.2) with g = ds/dW (11) on W = (xA., xB., a., phiA., phiB.) and, if h,
// h = ds/dX (9) on X = (xA, xB, a) and the pair (xA, a) dc/dx in Dcq. False if singular.
template <class T>
inline bool point_spin(const SpinPieces<T>& P, double xi, const T* a, const T* va, T& s, T* g, T* h,
                       double (*Dcq)[6]) {
  T cq[6], sq, hq[6];
  if (!(pair_spin(P.xA, a, P.vA, va, cq, sq, h ? hq : nullptr, Dcq) > kMinAlign)) return false;
  const double wa = 1.0 - xi;
  s = wa * (P.pA + P.nuA) + xi * (P.pB + P.nuB) - xi * P.sAB + sq;
  for (int i = 0; i < 3; ++i) {
    g[i] = wa * P.cA[i] - xi * P.cAB[i] + cq[i];
    g[3 + i] = xi * P.cB[i] - xi * P.cAB[3 + i];
    g[6 + i] = cq[3 + i];
  }
  g[9] = T(wa);
  g[10] = T(xi);
  if (h == nullptr) return true;
  for (int j = 0; j < 3; ++j) {
    h[j] = wa * P.hA[j] - xi * P.hAB[j] + hq[j];
    h[3 + j] = xi * P.hB[j] - xi * P.hAB[3 + j];
    h[6 + j] = hq[3 + j];
  }
  return true;
}

// r'(xi_q) and its rate (T = Dual: a with adot, and adot with addot).
template <class T>
inline void point_rates(const ElementInput& in, int q, const double* e, const double* ed,
                        const double* edd, T* a, T* va) {
  const double* c1 = in.n1 + 4 * q;
  double x[3] = {0.0, 0.0, 0.0}, xd[3] = {0.0, 0.0, 0.0}, xdd[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) {
      x[i] += c1[k] * e[kPosOff[k] + i];
      xd[i] += c1[k] * ed[kPosOff[k] + i];
      if (edd != nullptr) xdd[i] += c1[k] * edd[kPosOff[k] + i];
    }
  lift3<T>(x, xd, xdd, 0, a, va);
}

// Element inertial force fe = F (11.4) and, with Tangent, ke = ck dF/de + cv dF/dedot +
// ca dF/deddot (11.5); both overwritten. False if a smallest rotation is singular.
template <bool Tangent>
inline bool element_inertia(const ElementInput& in, const InertiaCoef& ic, const double* e,
                            const double* ed, const double* edd, const InertiaScales& sc,
                            double* fe, double* ke) {
  SpinPieces<Dual> P;
  if (!spin_pieces<Dual, Tangent>(in, e, ed, edd, P)) return false;
  alignas(64) double K[196] = {0.0};
  double F[14] = {0.0};
  const double c = sc.damping, ck = sc.ck, cv = sc.cv, ca = sc.ca;
  double kA = 0.0, kB = 0.0;  // sum_q ck w rho_polar (sdot + c s)(1 - xi), ... xi (11.5)
  for (int q = 0; q < in.nq; ++q) {
    const double xi = in.xi[q], w = in.gw[q] * in.j0[q];
    const double wp = w * ic.polar, wb = w * ic.bend;
    const double* n1 = in.n1 + 4 * q;
    Dual aq[3], vq[3], s, g[11], h[9];
    double Dcq[6][6];
    point_rates(in, q, e, ed, edd, aq, vq);
    if (!point_spin(P, xi, aq, vq, s, g, Tangent ? h : nullptr, Tangent ? Dcq : nullptr))
      return false;
    const double a[3] = {aq[0].v, aq[1].v, aq[2].v}, ad[3] = {vq[0].v, vq[1].v, vq[2].v};
    const double add[3] = {vq[0].d, vq[1].d, vq[2].d};
    const double n2 = dot3(a, a), n = std::sqrt(n2), in2 = 1.0 / n2, in3 = in2 / n;
    double axd[3], EL[3];
    cross3(a, ad, axd);
    for (int i = 0; i < 3; ++i) EL[i] = -axd[i] * in3;
    const double sdc = s.d + c * s.v;
    double f[11];
    for (int i = 0; i < 11; ++i) f[i] = wp * sdc * g[i].v;
    for (int i = 0; i < 3; ++i) f[6 + i] += wp * s.v * EL[i];
    const double aad = dot3(a, ad) * in2;
    double Qd[3] = {0.0, 0.0, 0.0}, Qdd[3] = {0.0, 0.0, 0.0};
    if (wb != 0.0) {  // bending rotary inertia ("full"): P addot / n^2 - 2 (a.adot / n^2) Q(adot)
      const double aadd = dot3(a, add) * in2;
      for (int i = 0; i < 3; ++i) {
        Qd[i] = (ad[i] - aad * a[i]) * in2;
        Qdd[i] = (add[i] - aadd * a[i]) * in2;
        f[6 + i] += wb * (Qdd[i] - 2.0 * aad * Qd[i] + c * Qd[i]);
      }
    }
    double f14[14];
    map_to_element(f, n1, f14);
    for (int i = 0; i < 14; ++i) F[i] += f14[i];
    if (!Tangent) continue;
    // rank-one parts: wp G (ca g + cv (gdot + h + c g) + ck (hdot + c h))^T + wp EL (cv g + ck h)^T
    double U[11], Z[11], El[11] = {0.0}, gv[11];
    for (int i = 0; i < 11; ++i) {
      const double hv = i < 9 ? h[i].v : 0.0, hd = i < 9 ? h[i].d : 0.0;
      gv[i] = wp * g[i].v;
      U[i] = ca * g[i].v + cv * (g[i].d + hv + c * g[i].v) + ck * (hd + c * hv);
      Z[i] = cv * g[i].v + ck * hv;
    }
    for (int i = 0; i < 3; ++i) El[6 + i] = wp * EL[i];
    double G14[14], U14[14], E14[14], Z14[14];
    map_to_element(gv, n1, G14);
    map_to_element(U, n1, U14);
    map_to_element(El, n1, E14);
    map_to_element(Z, n1, Z14);
    for (int r = 0; r < 14; ++r) {
      const double gr = G14[r], er = E14[r];
      double* row = K + 14 * r;
      for (int col = 0; col < 14; ++col) row[col] += gr * U14[col] + er * Z14[col];
    }
    // (sdot + c s) dG/de: the element pieces once per element (kA, kB), the pair (xA, a) here
    const double kap = ck * wp * sdc;
    kA += kap * (1.0 - xi);
    kB += kap * xi;
    double B[3][3];  // the a-a block before mapping
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        K[14 * (3 + i) + 3 + j] += kap * Dcq[i][j];
        B[i][j] = kap * Dcq[3 + i][3 + j];
      }
    for (int k = 0; k < 4; ++k) {
      const double kn = kap * n1[k];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          K[14 * (3 + i) + kPosOff[k] + j] += kn * Dcq[i][3 + j];
          K[14 * (kPosOff[k] + i) + 3 + j] += kn * Dcq[3 + i][j];
        }
    }
    // s (cv dEL/dadot + ck dEL/da): dEL/dadot = -[a x]/n^3, dEL/da = [adot x]/n^3 - 3 EL a^T/n^2
    const double ax[3][3] = {{0.0, -a[2], a[1]}, {a[2], 0.0, -a[0]}, {-a[1], a[0], 0.0}};
    const double dx[3][3] = {{0.0, -ad[2], ad[1]}, {ad[2], 0.0, -ad[0]}, {-ad[1], ad[0], 0.0}};
    const double ws = wp * s.v;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        B[i][j] += ws * (-cv * ax[i][j] * in3 + ck * (dx[i][j] * in3 - 3.0 * EL[i] * a[j] * in2));
    if (wb != 0.0) {  // bending (11.5): mass P/n^2, velocity and position derivatives
      double DQd[3][3], DQdd[3][3];
      dq_da(a, n2, ad, Qd, DQd);
      dq_da(a, n2, add, Qdd, DQdd);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double Pij = ((i == j ? 1.0 : 0.0) - a[i] * a[j] * in2) * in2;
          const double dv = -2.0 * (Qd[i] * a[j] * in2 + aad * Pij) + c * Pij;
          const double dk = DQdd[i][j] -
                            2.0 * (Qd[i] * (ad[j] - 2.0 * aad * a[j]) * in2 + aad * DQd[i][j]) +
                            c * DQd[i][j];
          B[i][j] += wb * (ca * Pij + cv * dv + ck * dk);
        }
    }
    for (int k = 0; k < 4; ++k)
      for (int l = 0; l < 4; ++l) {
        const double nkl = n1[k] * n1[l];
        double* blk = K + 14 * kPosOff[k] + kPosOff[l];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) blk[14 * i + j] += nkl * B[i][j];
      }
  }
  for (int i = 0; i < 14; ++i) fe[i] = F[i];
  if (!Tangent) return true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      K[14 * (3 + i) + 3 + j] += kA * P.DcA[i][j] - kB * P.DcAB[i][j];
      K[14 * (3 + i) + 10 + j] -= kB * P.DcAB[i][3 + j];
      K[14 * (10 + i) + 3 + j] -= kB * P.DcAB[3 + i][j];
      K[14 * (10 + i) + 10 + j] += kB * (P.DcB[i][j] - P.DcAB[3 + i][3 + j]);
    }
  for (int i = 0; i < 196; ++i) ke[i] = K[i];
  return true;
}

// Spin s and the point's r', r'-rate at every point, values only (energy, momentum). False if
// a smallest rotation is singular.
template <class Fn>
inline bool for_each_spin(const ElementInput& in, const double* e, const double* ed, Fn&& fn) {
  SpinPieces<double> P;
  if (!spin_pieces<double, false>(in, e, ed, nullptr, P)) return false;
  for (int q = 0; q < in.nq; ++q) {
    double a[3], ad[3], s, g[11];
    point_rates(in, q, e, ed, nullptr, a, ad);
    if (!point_spin<double>(P, in.xi[q], a, ad, s, g, nullptr, nullptr)) return false;
    fn(q, s, a, ad);
  }
  return true;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------------------
// Public API of the rotary inertia

// Inertial force fe[14] (11.4) at (e, ed, edd) and, if ke, ke[14*14] = ck dF/de + cv dF/ded +
// ca dF/dedd (11.5). NaN outputs at a singular smallest rotation (as forces()).
inline void inertia(const ElementInput& in, const InertiaCoef& ic, const double* e,
                    const double* ed, const double* edd, const InertiaScales& sc, double* fe,
                    double* ke) {
  const bool ok = ke ? detail::element_inertia<true>(in, ic, e, ed, edd, sc, fe, ke)
                     : detail::element_inertia<false>(in, ic, e, ed, edd, sc, fe, nullptr);
  if (!ok) {
    detail::fill_nan(fe, 14);
    if (ke) detail::fill_nan(ke, 196);
  }
}

// Rotary kinetic energy of the element (11.1). NaN at a singular smallest rotation.
inline double rotary_energy(const ElementInput& in, const InertiaCoef& ic, const double* e,
                            const double* ed) {
  double T = 0.0;
  const bool ok =
      detail::for_each_spin(in, e, ed, [&](int q, double s, const double* a, const double* ad) {
        const double n2 = detail::dot3(a, a), aad = detail::dot3(a, ad);
        const double pd2 = (detail::dot3(ad, ad) - aad * aad / n2) / n2;  // |P adot|^2 / n^2
        T += 0.5 * in.gw[q] * in.j0[q] * (ic.polar * s * s + ic.bend * pd2);
      });
  return ok ? T : detail::nan_value();
}

// Rotary angular momentum of the element, out[3] += sum_q w [rho_polar s t + rho_bend t x tdot].
inline void rotary_momentum(const ElementInput& in, const InertiaCoef& ic, const double* e,
                            const double* ed, double* out) {
  double L[3] = {0.0, 0.0, 0.0};
  const bool ok =
      detail::for_each_spin(in, e, ed, [&](int q, double s, const double* a, const double* ad) {
        const double w = in.gw[q] * in.j0[q], n2 = detail::dot3(a, a), n = std::sqrt(n2);
        double axd[3];
        detail::cross3(a, ad, axd);
        for (int i = 0; i < 3; ++i) L[i] += w * (ic.polar * s * a[i] / n + ic.bend * axd[i] / n2);
      });
  for (int i = 0; i < 3; ++i) out[i] += ok ? L[i] : detail::nan_value();
}

// Re-referencing a node (11.6) keeps its spin phidot + nu and spin rate phiddot + nudot: with the
// new reference tref = t the node's nu vanishes, so nu and its time derivative (at the old
// reference) are added to the twist rate and its acceleration.
inline void rereference_rates(const double* tref, const double* x, const double* xd,
                              const double* xdd, double& phid, double& phidd) {
  detail::Dual X[3], W[3], c[3], nu;
  for (int i = 0; i < 3; ++i) {
    X[i] = detail::Dual(x[i], xd[i]);
    W[i] = detail::Dual(xd[i], xdd[i]);
  }
  detail::node_spin<detail::Dual>(X, W, tref, c, nu, nullptr, nullptr);
  phid += nu.v;
  phidd += nu.d;
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_INERTIA_HPP
