// rod_inertia.hpp -- the rod's rotary inertia (docs/rod-derivation.md section 11): the kinetic
// energy of the cross-sections' rotation with the exact spin s = omega . t of the material frame,
// the configuration-dependent mass matrix, the gyroscopic forces and their exact tangents. Part of
// the rod kernel (rod_kernel.hpp includes it).
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

#include "rod_common.hpp"

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

// A value and its time derivative (forward mode along the motion).
struct Dual {
  double v = 0.0, d = 0.0;
  Dual() = default;
  Dual(double x, double dx = 0.0) : v(x), d(dx) {}  // NOLINT: implicit from double on purpose
};
inline Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
inline Dual operator*(double s, Dual a) { return {s * a.v, s * a.d}; }
inline Dual operator*(Dual a, double s) { return {s * a.v, s * a.d}; }
inline Dual operator/(double s, Dual a) {
  const double r = s / a.v;
  return {r, -r * a.d / a.v};
}
inline Dual sqrt(Dual a) {
  const double r = std::sqrt(a.v);
  return {r, 0.5 * a.d / r};
}
inline double val(double x) { return x; }
inline double val(Dual x) { return x.v; }

// Node spin coefficient (11.3): nu = c . xdot with c = (x x tr) / E, E = |x| (|x| + tr . x), and
// Dc = dc/dx = -[tr x] / E - c (dE/dx)^T / E, dE/dx = 2 x + (tr . x) x / |x| + |x| tr.
// Returns the alignment 1 + tr . t.
template <class T>
inline double node_coef(const T* x, const double* tr, T* c, T (*Dc)[3]) {
  using std::sqrt;
  const T s = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  const T tx = tr[0] * x[0] + tr[1] * x[1] + tr[2] * x[2];
  const T iE = 1.0 / (s * (s + tx));
  c[0] = (x[1] * tr[2] - x[2] * tr[1]) * iE;
  c[1] = (x[2] * tr[0] - x[0] * tr[2]) * iE;
  c[2] = (x[0] * tr[1] - x[1] * tr[0]) * iE;
  const double align = 1.0 + val(tx) / val(s);
  if (Dc == nullptr) return align;
  const T txs = tx * (1.0 / s);
  T q[3];
  for (int j = 0; j < 3; ++j) q[j] = 2.0 * x[j] + txs * x[j] + s * tr[j];
  const double trx[3][3] = {{0.0, -tr[2], tr[1]}, {tr[2], 0.0, -tr[0]}, {-tr[1], tr[0], 0.0}};
  for (int i = 0; i < 3; ++i) {
    const T ci = c[i] * iE;
    for (int j = 0; j < 3; ++j) Dc[i][j] = -trx[i][j] * iE - ci * q[j];
  }
  return align;
}

// Pair spin coefficients (11.3): sigma = c1 . xdot1 + c2 . xdot2, k = x2 x x1,
// D = |x1||x2| + x1 . x2, ci = k / (|xi| D). Dc (6 x 6): rows (c1, c2), columns (x1, x2):
//   dc1/dx1 = [x2 x]/(s1 D) - c1 (t1/s1 + e1)^T,  dc1/dx2 = -[x1 x]/(s1 D) - c1 e2^T
//   dc2/dx1 = [x2 x]/(s2 D) - c2 e1^T,            dc2/dx2 = -[x1 x]/(s2 D) - c2 (t2/s2 + e2)^T
// with e1 = (s2 t1 + x2)/D, e2 = (s1 t2 + x1)/D. Returns the alignment 1 + t1 . t2.
template <class T>
inline double pair_coef(const T* x1, const T* x2, T* c, T (*Dc)[6]) {
  using std::sqrt;
  const T s1 = sqrt(x1[0] * x1[0] + x1[1] * x1[1] + x1[2] * x1[2]);
  const T s2 = sqrt(x2[0] * x2[0] + x2[1] * x2[1] + x2[2] * x2[2]);
  const T s12 = s1 * s2;
  const T x12 = x1[0] * x2[0] + x1[1] * x2[1] + x1[2] * x2[2];
  const T D = s12 + x12;
  const T iD = 1.0 / D;
  const T i1 = 1.0 / (s1 * D), i2 = 1.0 / (s2 * D);
  const T k[3] = {x2[1] * x1[2] - x2[2] * x1[1], x2[2] * x1[0] - x2[0] * x1[2],
                  x2[0] * x1[1] - x2[1] * x1[0]};
  for (int i = 0; i < 3; ++i) {
    c[i] = k[i] * i1;
    c[3 + i] = k[i] * i2;
  }
  const double align = 1.0 + val(x12) / val(s12);
  if (Dc == nullptr) return align;
  const T is1 = 1.0 / s1, is2 = 1.0 / s2;
  T e1[3], e2[3], u1[3], u2[3];  // u1 = t1/s1 + e1, u2 = t2/s2 + e2
  for (int j = 0; j < 3; ++j) {
    e1[j] = (s2 * is1 * x1[j] + x2[j]) * iD;
    e2[j] = (s1 * is2 * x2[j] + x1[j]) * iD;
    u1[j] = x1[j] * is1 * is1 + e1[j];
    u2[j] = x2[j] * is2 * is2 + e2[j];
  }
  const T X2[3][3] = {{0.0, -1.0 * x2[2], x2[1]}, {x2[2], 0.0, -1.0 * x2[0]},
                      {-1.0 * x2[1], x2[0], 0.0}};
  const T X1[3][3] = {{0.0, -1.0 * x1[2], x1[1]}, {x1[2], 0.0, -1.0 * x1[0]},
                      {-1.0 * x1[1], x1[0], 0.0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Dc[i][j] = X2[i][j] * i1 - c[i] * u1[j];
      Dc[i][3 + j] = -1.0 * X1[i][j] * i1 - c[i] * e2[j];
      Dc[3 + i][j] = X2[i][j] * i2 - c[3 + i] * e1[j];
      Dc[3 + i][3 + j] = -1.0 * X1[i][j] * i2 - c[3 + i] * u2[j];
    }
  return align;
}

// r'(xi_q), its velocity and acceleration (a, adot, addot).
inline void point_rates(const ElementInput& in, int q, const double* e, const double* ed,
                        const double* edd, double* a, double* ad, double* add) {
  const double* c1 = in.n1 + 4 * q;
  for (int i = 0; i < 3; ++i) {
    a[i] = ad[i] = add[i] = 0.0;
    for (int k = 0; k < 4; ++k) {
      a[i] += c1[k] * e[kPosOff[k] + i];
      ad[i] += c1[k] * ed[kPosOff[k] + i];
      if (edd) add[i] += c1[k] * edd[kPosOff[k] + i];
    }
  }
}

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
      D[i][j] = (-(aw * (i == j ? 1.0 : 0.0) + a[i] * w[j]) * in2 + 2.0 * aw * a[i] * a[j] * in2 * in2) *
                    in2 -
                2.0 * Qw[i] * a[j] * in2;
}

// Per-element spin pieces, with time derivatives: nodal and pair coefficients and their
// gradients h = (dc/dx)^T xdot (11.3).
struct SpinPieces {
  Dual xA[3], xB[3], vA[3], vB[3], pA, pB;
  Dual cA[3], DcA[3][3], cB[3], DcB[3][3], cAB[6], DcAB[6][6];
  Dual nuA, nuB, sAB, hA[3], hB[3], hAB[6];
};

// Fills the pieces; false if a smallest rotation is singular.
inline bool spin_pieces(const ElementInput& in, const double* e, const double* ed,
                        const double* edd, SpinPieces& P) {
  for (int i = 0; i < 3; ++i) {
    P.xA[i] = Dual(e[3 + i], ed[3 + i]);
    P.xB[i] = Dual(e[10 + i], ed[10 + i]);
    P.vA[i] = Dual(ed[3 + i], edd ? edd[3 + i] : 0.0);
    P.vB[i] = Dual(ed[10 + i], edd ? edd[10 + i] : 0.0);
  }
  P.pA = Dual(ed[6], edd ? edd[6] : 0.0);
  P.pB = Dual(ed[13], edd ? edd[13] : 0.0);
  double al = node_coef(P.xA, in.tref_a, P.cA, P.DcA);
  al = std::min(al, node_coef(P.xB, in.tref_b, P.cB, P.DcB));
  al = std::min(al, pair_coef(P.xA, P.xB, P.cAB, P.DcAB));
  if (!(al > kMinAlign)) return false;
  const Dual W[6] = {P.vA[0], P.vA[1], P.vA[2], P.vB[0], P.vB[1], P.vB[2]};
  P.nuA = P.cA[0] * P.vA[0] + P.cA[1] * P.vA[1] + P.cA[2] * P.vA[2];
  P.nuB = P.cB[0] * P.vB[0] + P.cB[1] * P.vB[1] + P.cB[2] * P.vB[2];
  P.sAB = Dual(0.0);
  for (int i = 0; i < 6; ++i) P.sAB = P.sAB + P.cAB[i] * W[i];
  for (int j = 0; j < 3; ++j) {
    P.hA[j] = P.DcA[0][j] * P.vA[0] + P.DcA[1][j] * P.vA[1] + P.DcA[2][j] * P.vA[2];
    P.hB[j] = P.DcB[0][j] * P.vB[0] + P.DcB[1][j] * P.vB[1] + P.DcB[2][j] * P.vB[2];
  }
  for (int j = 0; j < 6; ++j) {
    P.hAB[j] = Dual(0.0);
    for (int i = 0; i < 6; ++i) P.hAB[j] = P.hAB[j] + P.DcAB[i][j] * W[i];
  }
  return true;
}

// Spin at point q (11.2) with g = ds/dW (11) and h = ds/dX (9) on W = (xA., xB., a., phiA.,
// phiB.), X = (xA, xB, a); the pair (xA, a) coefficients in cq, Dcq. False if singular.
inline bool point_spin(const SpinPieces& P, double xi, const double* a, const double* ad,
                       const double* add, Dual& s, Dual* g, Dual* h, Dual* cq, Dual (*Dcq)[6]) {
  Dual xa[3], va[3];
  for (int i = 0; i < 3; ++i) {
    xa[i] = Dual(a[i], ad[i]);
    va[i] = Dual(ad[i], add[i]);
  }
  if (!(pair_coef(P.xA, xa, cq, Dcq) > kMinAlign)) return false;
  const Dual Wq[6] = {P.vA[0], P.vA[1], P.vA[2], va[0], va[1], va[2]};
  Dual sq(0.0);
  for (int i = 0; i < 6; ++i) sq = sq + cq[i] * Wq[i];
  const double wa = 1.0 - xi;
  s = wa * (P.pA + P.nuA) + xi * (P.pB + P.nuB) - xi * P.sAB + sq;
  for (int i = 0; i < 3; ++i) {
    g[i] = wa * P.cA[i] - xi * P.cAB[i] + cq[i];
    g[3 + i] = xi * P.cB[i] - xi * P.cAB[3 + i];
    g[6 + i] = cq[3 + i];
  }
  g[9] = Dual(wa);
  g[10] = Dual(xi);
  if (h == nullptr) return true;
  for (int j = 0; j < 3; ++j) {
    Dual hq0(0.0), hq1(0.0);
    for (int i = 0; i < 6; ++i) {
      hq0 = hq0 + Dcq[i][j] * Wq[i];
      hq1 = hq1 + Dcq[i][3 + j] * Wq[i];
    }
    h[j] = wa * P.hA[j] - xi * P.hAB[j] + hq0;
    h[3 + j] = xi * P.hB[j] - xi * P.hAB[3 + j];
    h[6 + j] = hq1;
  }
  return true;
}

// Element inertial force fe = F (11.4) and, with Tangent, ke = ck dF/de + cv dF/dedot +
// ca dF/deddot (11.5); both overwritten. False if a smallest rotation is singular.
template <bool Tangent>
inline bool element_inertia(const ElementInput& in, const InertiaCoef& ic, const double* e,
                            const double* ed, const double* edd, const InertiaScales& sc,
                            double* fe, double* ke) {
  SpinPieces P;
  if (!spin_pieces(in, e, ed, edd, P)) return false;
  for (int i = 0; i < 14; ++i) fe[i] = 0.0;
  if (Tangent)
    for (int i = 0; i < 196; ++i) ke[i] = 0.0;
  const double c = sc.damping, ck = sc.ck, cv = sc.cv, ca = sc.ca;
  double kA = 0.0, kB = 0.0;  // sum_q ck w rho_polar (sdot + c s)(1 - xi), ... xi (11.5)
  for (int q = 0; q < in.nq; ++q) {
    const double xi = in.xi[q], w = in.gw[q] * in.j0[q];
    const double wp = w * ic.polar, wb = w * ic.bend;
    const double* n1 = in.n1 + 4 * q;
    double a[3], ad[3], add[3];
    point_rates(in, q, e, ed, edd, a, ad, add);
    Dual s, g[11], h[9], cq[6], Dcq[6][6];
    if (!point_spin(P, xi, a, ad, add, s, g, Tangent ? h : nullptr, cq, Dcq)) return false;
    const double n2 = dot3(a, a), n = std::sqrt(n2), in2 = 1.0 / n2, in3 = in2 / n;
    double axd[3], EL[3];
    cross3(a, ad, axd);
    for (int i = 0; i < 3; ++i) EL[i] = -axd[i] * in3;
    const double sdc = s.d + c * s.v;
    double f[11];
    for (int i = 0; i < 11; ++i) f[i] = wp * sdc * g[i].v;
    for (int i = 0; i < 3; ++i) f[6 + i] += wp * s.v * EL[i];
    const double aad = dot3(a, ad) * in2;
    double Qd[3], Qdd[3];
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
    for (int i = 0; i < 14; ++i) fe[i] += f14[i];
    if (!Tangent) continue;
    // rank-one parts: wp G (ca g + cv (gdot + h + c g) + ck (hdot + c h))^T + wp EL (cv g + ck h)^T
    double U[11], Z[11], El[11] = {0.0}, gv[11];
    for (int i = 0; i < 11; ++i) {
      const double hv = i < 9 ? h[i].v : 0.0, hd = i < 9 ? h[i].d : 0.0;
      gv[i] = g[i].v;
      U[i] = ca * g[i].v + cv * (g[i].d + hv + c * g[i].v) + ck * (hd + c * hv);
      Z[i] = cv * g[i].v + ck * hv;
    }
    for (int i = 0; i < 3; ++i) El[6 + i] = EL[i];
    double G14[14], U14[14], E14[14], Z14[14];
    map_to_element(gv, n1, G14);
    map_to_element(U, n1, U14);
    map_to_element(El, n1, E14);
    map_to_element(Z, n1, Z14);
    for (int r = 0; r < 14; ++r) {
      const double gr = wp * G14[r], er = wp * E14[r];
      double* row = ke + 14 * r;
      for (int col = 0; col < 14; ++col) row[col] += gr * U14[col] + er * Z14[col];
    }
    // (sdot + c s) dG/de: the element pieces once per element (kA, kB), the pair (xA, a) here
    const double kap = ck * wp * sdc;
    kA += kap * (1.0 - xi);
    kB += kap * xi;
    double B[3][3];  // the a-a block before mapping
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        ke[14 * (3 + i) + 3 + j] += kap * Dcq[i][j].v;
        B[i][j] = kap * Dcq[3 + i][3 + j].v;
      }
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          ke[14 * (3 + i) + kPosOff[k] + j] += kap * n1[k] * Dcq[i][3 + j].v;
          ke[14 * (kPosOff[k] + i) + 3 + j] += kap * n1[k] * Dcq[3 + i][j].v;
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
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) ke[14 * (kPosOff[k] + i) + kPosOff[l] + j] += nkl * B[i][j];
      }
  }
  if (Tangent)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        ke[14 * (3 + i) + 3 + j] += kA * P.DcA[i][j].v - kB * P.DcAB[i][j].v;
        ke[14 * (3 + i) + 10 + j] -= kB * P.DcAB[i][3 + j].v;
        ke[14 * (10 + i) + 3 + j] -= kB * P.DcAB[3 + i][j].v;
        ke[14 * (10 + i) + 10 + j] += kB * (P.DcB[i][j].v - P.DcAB[3 + i][3 + j].v);
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
  detail::SpinPieces P;
  if (!detail::spin_pieces(in, e, ed, nullptr, P)) return detail::nan_value();
  double T = 0.0;
  for (int q = 0; q < in.nq; ++q) {
    double a[3], ad[3], add[3];
    detail::point_rates(in, q, e, ed, nullptr, a, ad, add);
    detail::Dual s, g[11], cq[6], Dcq[6][6];
    if (!detail::point_spin(P, in.xi[q], a, ad, add, s, g, nullptr, cq, Dcq))
      return detail::nan_value();
    const double n2 = detail::dot3(a, a), aad = detail::dot3(a, ad);
    const double pd2 = (detail::dot3(ad, ad) - aad * aad / n2) / n2;  // |P adot|^2 / n^2
    T += 0.5 * in.gw[q] * in.j0[q] * (ic.polar * s.v * s.v + ic.bend * pd2);
  }
  return T;
}

// Rotary angular momentum of the element, out[3] += sum_q w [rho_polar s t + rho_bend t x tdot].
inline void rotary_momentum(const ElementInput& in, const InertiaCoef& ic, const double* e,
                            const double* ed, double* out) {
  detail::SpinPieces P;
  if (!detail::spin_pieces(in, e, ed, nullptr, P)) {
    detail::fill_nan(out, 3);
    return;
  }
  for (int q = 0; q < in.nq; ++q) {
    double a[3], ad[3], add[3], axd[3];
    detail::point_rates(in, q, e, ed, nullptr, a, ad, add);
    detail::Dual s, g[11], cq[6], Dcq[6][6];
    if (!detail::point_spin(P, in.xi[q], a, ad, add, s, g, nullptr, cq, Dcq)) {
      detail::fill_nan(out, 3);
      return;
    }
    const double w = in.gw[q] * in.j0[q], n2 = detail::dot3(a, a), n = std::sqrt(n2);
    detail::cross3(a, ad, axd);
    for (int i = 0; i < 3; ++i) out[i] += w * (ic.polar * s.v * a[i] / n + ic.bend * axd[i] / n2);
  }
}

// Re-referencing a node (11.6) keeps its spin phidot + nu and spin rate phiddot + nudot: with the
// new reference tref = t the node's nu vanishes, so nu and its time derivative (at the old
// reference) are added to the twist rate and its acceleration.
inline void rereference_rates(const double* tref, const double* x, const double* xd,
                              const double* xdd, double& phid, double& phidd) {
  detail::Dual X[3], c[3];
  for (int i = 0; i < 3; ++i) X[i] = detail::Dual(x[i], xd[i]);
  detail::node_coef(X, tref, c, static_cast<detail::Dual(*)[3]>(nullptr));
  detail::Dual nu(0.0);
  for (int i = 0; i < 3; ++i) nu = nu + c[i] * detail::Dual(xd[i], xdd[i]);
  phid += nu.v;
  phidd += nu.d;
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_INERTIA_HPP
