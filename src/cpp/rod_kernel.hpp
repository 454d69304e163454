// rod_kernel.hpp -- spatial Kirchhoff rod with torsion on a rational ANCF (RANCF) cable centerline.
//
// Formulation: docs/rod-derivation.md (smallest-rotation triads plus an interpolated relative
// twist, after Meier, Popp & Wall 2014, CMAME 278). Centerline interpolation: rancf-math.md
// sections 3 and 6. Derivation of every formula below, in the order of the code:
// docs/rod-derivation.md.
//
// Header-only, dependency-free C++17. Plain pointers, row-major matrices.
//
// Element coordinates e[14]: node A = e[0..6] = (rA, rA_x, phiA), node B = e[7..13] = (rB, rB_x,
// phiB).
//
// Structure of the computation (docs/rod-derivation.md section 0), all derivatives hand-derived:
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
#ifndef RANCF_ROD_KERNEL_HPP
#define RANCF_ROD_KERNEL_HPP

#include <algorithm>
#include <cmath>

namespace rancf::rod {

struct Stiffness {
  double ea, gj, ei2, ei3;
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

// Smallest admissible value of 1 + a.b in a smallest rotation SR(a -> b) (see the header comment).
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

// ---------------------------------------------------------------------------------------------------------
// Nodal triad, values only (rod-math section 2, docs/rod-derivation.md 1). Returns 1 + tref.t (the
// SR alignment).
//   t = x/|x|,  u = SR(tr -> t) mr = mr - (t.mr)/(1 + tr.t) (t + tr),  v = SR(tr -> t)(tr x mr) (=
//   t x u), m1 = cos(phi) u + sin(phi) v,  m2 = t x m1 = cos(phi) v - sin(phi) u.
inline double triad_value(const double* tr, const double* mr, const double* x, double phi,
                          double* t, double* u, double* v, double* m1, double* m2) {
  const double s = std::sqrt(dot3(x, x));
  for (int i = 0; i < 3; ++i) t[i] = x[i] / s;
  const double p = 1.0 + dot3(tr, t);
  double m2r[3];
  cross3(tr, mr, m2r);
  const double ku = dot3(t, mr) / p, kv = dot3(t, m2r) / p;
  const double c = std::cos(phi), sn = std::sin(phi);
  for (int i = 0; i < 3; ++i) {
    const double w = t[i] + tr[i];
    u[i] = mr[i] - ku * w;
    v[i] = m2r[i] - kv * w;
    m1[i] = c * u[i] + sn * v[i];
    m2[i] = c * v[i] - sn * u[i];
  }
  return p;
}

// Node A's transported frame (t, u, v) with first derivatives with respect to x = r_x, and the
// scalar ingredients of the second derivatives (docs/rod-derivation.md 1). dt[i][j] = d t_i / d x_j
// (= Pt, symmetric), du, dv likewise. u = mr - ku (t + tr), v = m2r - kv (t + tr), ku = t.mr/p, kv
// = t.m2r/p, p = 1 + tr.t. Second derivatives are never stored as tensors: only their contractions
// with vectors are needed, via
//   sum_i g_i d2t_i/dx dx = -(g t^T + t g^T + (g.t)(I - 3 t t^T))/s^2 (contract_t) sum_i g_i
//   d2u_i/dx dx = contract_t(-ku g) - (g.w) d2ku - (Pt g) dku^T - dku (Pt g)^T,  w = t + tr.
struct FrameJet {
  double t[3], u[3], v[3], w[3];
  double s, align;  // |x|, 1 + tr.t
  double dt[3][3], du[3][3], dv[3][3];
  double ku, kv, dku[3], dkv[3], d2ku[3][3], d2kv[3][3];
};

// C = sum_i g_i d2t_i/dx dx (symmetric 3x3).
inline void contract_t(const double* g, const double* t, double s, double (*C)[3]) {
  const double gt = dot3(g, t), is2 = 1.0 / (s * s);
  for (int j = 0; j < 3; ++j)
    for (int l = 0; l < 3; ++l)
      C[j][l] =
          -(g[j] * t[l] + t[j] * g[l] + gt * ((j == l ? 1.0 : 0.0) - 3.0 * t[j] * t[l])) * is2;
}

template <bool WithH>
inline void frame_jet(const double* tr, const double* mr, const double* x, FrameJet& J) {
  const double s = std::sqrt(dot3(x, x)), sinv = 1.0 / s;
  J.s = s;
  double* t = J.t;
  for (int i = 0; i < 3; ++i) t[i] = x[i] * sinv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) J.dt[i][j] = ((i == j ? 1.0 : 0.0) - t[i] * t[j]) * sinv;
  const double p = 1.0 + dot3(tr, t), ip = 1.0 / p;
  J.align = p;
  double m2r[3], dp[3];
  cross3(tr, mr, m2r);
  for (int j = 0; j < 3; ++j) dp[j] = dot3(J.dt[j], tr);
  J.ku = dot3(t, mr) * ip;
  J.kv = dot3(t, m2r) * ip;
  for (int j = 0; j < 3; ++j) {
    J.dku[j] = (dot3(J.dt[j], mr) - J.ku * dp[j]) * ip;
    J.dkv[j] = (dot3(J.dt[j], m2r) - J.kv * dp[j]) * ip;
  }
  for (int i = 0; i < 3; ++i) {
    J.w[i] = t[i] + tr[i];
    J.u[i] = mr[i] - J.ku * J.w[i];
    J.v[i] = m2r[i] - J.kv * J.w[i];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      J.du[i][j] = -J.dku[j] * J.w[i] - J.ku * J.dt[i][j];
      J.dv[i][j] = -J.dkv[j] * J.w[i] - J.kv * J.dt[i][j];
    }
  if (!WithH) return;
  // d2k = (d2q - k d2p - dk dp^T - dp dk^T)/p with d2q = contract_t(w0), d2p = contract_t(tr)
  double c1[3], c2[3], Cu[3][3], Cv[3][3];
  for (int i = 0; i < 3; ++i) {
    c1[i] = mr[i] - J.ku * tr[i];
    c2[i] = m2r[i] - J.kv * tr[i];
  }
  contract_t(c1, t, s, Cu);
  contract_t(c2, t, s, Cv);
  for (int j = 0; j < 3; ++j)
    for (int l = 0; l < 3; ++l) {
      J.d2ku[j][l] = (Cu[j][l] - J.dku[j] * dp[l] - dp[j] * J.dku[l]) * ip;
      J.d2kv[j][l] = (Cv[j][l] - J.dkv[j] * dp[l] - dp[j] * J.dkv[l]) * ip;
    }
}

// ---------------------------------------------------------------------------------------------------------
// Relative twist (rod-math 3, docs/rod-derivation.md 2). With m1_N = R_{t_N}(phi_N) u_N (rotation
// about t_N) and SR(tA -> tB) R_{tA}(phiA) = R_{tB}(phiA) SR(tA -> tB):
//   alpha_B = wrap(phiB - phiA + beta),  beta = atan2(Y, X) = angle about tB from SR(tA -> tB) uA
//   to uB, X = uB.uA - (tB.uA)(uB.tA)/(1 + tA.tB),  Y = uB.vA - (tB.vA)(uB.tA)/(1 + tA.tB),
// wrap() maps to [-pi, pi) (the atan2 branch of rod-math 3). beta depends on (rA_x, rB_x) only, so
// the Hessian of alpha_B is the 6x6 Hessian of beta.
inline double wrap_pi(double a) {
  constexpr double pi = 3.14159265358979323846;
  return a - 2.0 * pi * std::floor((a + pi) / (2.0 * pi));
}

inline double beta_value(const double* tA, const double* uA, const double* vA, const double* tB,
                         const double* uB, double& align) {
  align = 1.0 + dot3(tA, tB);
  const double g = dot3(uB, tA) / align;
  return std::atan2(dot3(uB, vA) - dot3(tB, vA) * g, dot3(uB, uA) - dot3(tB, uA) * g);
}

// Gradient and Hessian of beta (docs/rod-derivation.md 2). beta depends on the nodal tangents only.
// With the twist vector of a smallest rotation, V(t, r) = (t x r)/(1 + r.t), the first variation is
//   d beta = (V(tB, trB) + V(tA, tB)) . dtB + (V(tA, tB) - V(tA, trA)) . dtA =: WB . dtB + WA .
//   dtA,
// (axial spin of node B's transported frame, minus that of node A's, minus the twist of SR(tA ->
// tB)). WN is perpendicular to tN, so grad_{xN} beta = WN/sN (sN = |xN|), and
//   H_NN = [ dWN/dtN (I - tN tN^T) - WN tN^T ]/sN^2,  H_BA = dWB/dtA (I - tA tA^T)/(sA sB),
// with dV/dt = -([r x] + V r^T)/(1 + r.t) and dV/dr = ([t x] - V t^T)/(1 + r.t).
inline void sr_twist(const double* t, const double* r, double* V, double (*Mt)[3],
                     double (*Mr)[3]) {
  const double ip = 1.0 / (1.0 + dot3(r, t));
  double txr[3];
  cross3(t, r, txr);
  for (int i = 0; i < 3; ++i) V[i] = txr[i] * ip;
  if (Mt) {  // -([r x] + V r^T) ip
    const double rx[3][3] = {{0.0, -r[2], r[1]}, {r[2], 0.0, -r[0]}, {-r[1], r[0], 0.0}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Mt[i][j] = -(rx[i][j] + V[i] * r[j]) * ip;
  }
  if (Mr) {  // ([t x] - V t^T) ip
    const double tx[3][3] = {{0.0, -t[2], t[1]}, {t[2], 0.0, -t[0]}, {-t[1], t[0], 0.0}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Mr[i][j] = (tx[i][j] - V[i] * t[j]) * ip;
  }
}

// gb[6] = d beta/d(rA_x, rB_x); if WithH, Hb[6][6] its Hessian.
template <bool WithH>
inline void beta_derivs(const double* tA, double sA, const double* trA, const double* tB, double sB,
                        const double* trB, double* gb, double (*Hb)[6]) {
  double VA1[3], VB1[3], VAB[3], MA1[3][3], MB1[3][3], MABa[3][3], MABb[3][3];
  sr_twist(tA, trA, VA1, WithH ? MA1 : nullptr, nullptr);
  sr_twist(tB, trB, VB1, WithH ? MB1 : nullptr, nullptr);
  sr_twist(tA, tB, VAB, WithH ? MABa : nullptr, WithH ? MABb : nullptr);
  double WA[3], WB[3];
  for (int i = 0; i < 3; ++i) {
    WA[i] = VAB[i] - VA1[i];
    WB[i] = VB1[i] + VAB[i];
    gb[i] = WA[i] / sA;
    gb[3 + i] = WB[i] / sB;
  }
  if (!WithH) return;
  // dWA/dtA = MABa - MA1, dWB/dtB = MB1 + MABb, dWB/dtA = MABa
  const double iA2 = 1.0 / (sA * sA), iB2 = 1.0 / (sB * sB), iAB = 1.0 / (sA * sB);
  double DA[3][3], DB[3][3], DX[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      DA[i][j] = MABa[i][j] - MA1[i][j];
      DB[i][j] = MB1[i][j] + MABb[i][j];
      DX[i][j] = MABa[i][j];
    }
  // right-multiply by the projector (I - t t^T): M - (M t) t^T
  double DAt[3], DBt[3], DXt[3];
  for (int i = 0; i < 3; ++i) {
    DAt[i] = dot3(DA[i], tA);
    DBt[i] = dot3(DB[i], tB);
    DXt[i] = dot3(DX[i], tA);
  }
  double HAA[3][3], HBB[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      HAA[i][j] = (DA[i][j] - (DAt[i] + WA[i]) * tA[j]) * iA2;
      HBB[i][j] = (DB[i][j] - (DBt[i] + WB[i]) * tB[j]) * iB2;
      const double hba = (DX[i][j] - DXt[i] * tA[j]) * iAB;  // row B i, column A j
      Hb[3 + i][j] = hba;
      Hb[j][3 + i] = hba;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {  // symmetric by construction; average the round-off
      Hb[i][j] = Hb[j][i] = 0.5 * (HAA[i][j] + HAA[j][i]);
      Hb[3 + i][3 + j] = Hb[3 + j][3 + i] = 0.5 * (HBB[i][j] + HBB[j][i]);
    }
}

// ---------------------------------------------------------------------------------------------------------
// Material curvatures at a quadrature point (docs/rod-derivation.md 3). Local frame: node A's triad
// at phiA = 0, (tA, uA, vA); a = r', b = r'' in that frame; the twist angle of the material triad
// at xi about the transported frame is theta = phiA + xi alpha_B:
//   n = |a|, d = n + a0 (= n (1 + tA.t)), rho = 1/n^2, B = n b0 + a.b, sigma = B/(n^3 d), h = a2 b1
//   - a1 b2, P = a2 sigma - b2 rho (= kappa.SR(uA)), Q = b1 rho - a1 sigma (= kappa.SR(vA)), tau =
//   h/(n^2 d), K1 = alpha_B/n + tau, K2 = cos(theta) P + sin(theta) Q, K3 = cos(theta) Q -
//   sin(theta) P.
// Returns false if 1 + tA.t <= kMinAlign.
inline bool qcurv(const double* a, const double* b, double aB, double th, double* K, double& n2) {
  n2 = dot3(a, a);
  const double n = std::sqrt(n2);
  const double d = n + a[0];
  if (!(d > kMinAlign * n)) return false;
  const double rho = 1.0 / n2;
  const double sigma = (n * b[0] + dot3(a, b)) * rho / (n * d);
  const double h = a[2] * b[1] - a[1] * b[2];
  const double P = a[2] * sigma - b[2] * rho, Q = b[1] * rho - a[1] * sigma;
  const double C = std::cos(th), S = std::sin(th);
  K[0] = aB / n + h * rho / d;
  K[1] = C * P + S * Q;
  K[2] = C * Q - S * P;
  return true;
}

// Energy density f (times W = gw j0), its gradient g[8] and (if WithH) Hessian H[8][8] (upper
// triangle) in the variables (a0, a1, a2, b0, b1, b2, phiA, alpha_B) (docs/rod-derivation.md 4). th
// = phiA + xi alpha_B.
template <bool WithH>
inline bool qdensity(const double* ain, const double* bin, double aB, double th, double xi,
                     double W, double j0, const double* k0, const Stiffness& s, double& f,
                     double* g, double (*H)[8]) {
  const double a[3] = {ain[0], ain[1], ain[2]}, b[3] = {bin[0], bin[1], bin[2]};
  const double n2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2], n = std::sqrt(n2);
  const double d = n + a[0];
  if (!(d > kMinAlign * n)) return false;
  const double invn = 1.0 / n, rho = invn * invn, invd = 1.0 / d;
  const double t[3] = {a[0] * invn, a[1] * invn, a[2] * invn};
  const double w[3] = {t[0] + 1.0, t[1], t[2]};
  const double B = n * b[0] + a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double psi = rho * invd, chi = psi * invn;
  const double sigma = B * chi;
  const double h = a[2] * b[1] - a[1] * b[2];
  const double P = a[2] * sigma - b[2] * rho, Q = b[1] * rho - a[1] * sigma;
  const double C = std::cos(th), S = std::sin(th);
  const double K1 = aB * invn + h * psi;
  const double K2 = C * P + S * Q, K3 = C * Q - S * P;
  const double ij2 = 1.0 / (j0 * j0);
  const double eps = 0.5 * (n2 * ij2 - 1.0);
  const double r1 = K1 - k0[0], r2 = K2 - k0[1], r3 = K3 - k0[2];
  f = 0.5 * W * (s.ea * eps * eps + s.gj * r1 * r1 + s.ei2 * r2 * r2 + s.ei3 * r3 * r3);

  // gradients of the intermediates over x = (a, b); chi, psi, rho depend on a only
  double g3[3], g2[3], gchi[3], gpsi[3], grho[3];
  for (int i = 0; i < 3; ++i) {
    const double ti = t[i] * invn, wi = w[i] * invd;
    g3[i] = -3.0 * ti - wi;
    g2[i] = -2.0 * ti - wi;
    gchi[i] = chi * g3[i];
    gpsi[i] = psi * g2[i];
    grho[i] = -2.0 * rho * ti;
  }
  const double gB[6] = {b[0] * w[0], b[0] * t[1] + b[1], b[0] * t[2] + b[2], d, a[1], a[2]};
  const double gh[6] = {0.0, -b[2], b[1], 0.0, a[2], -a[1]};
  double gsig[6], gK1[6], gK2[6], gK3[6];
  for (int i = 0; i < 3; ++i) gsig[i] = chi * gB[i] + B * gchi[i];
  for (int i = 3; i < 6; ++i) gsig[i] = chi * gB[i];
  {
    double gP[6], gQ[6];
    for (int i = 0; i < 3; ++i) {
      gP[i] = a[2] * gsig[i] - b[2] * grho[i];
      gQ[i] = b[1] * grho[i] - a[1] * gsig[i];
    }
    for (int i = 3; i < 6; ++i) {
      gP[i] = a[2] * gsig[i];
      gQ[i] = -a[1] * gsig[i];
    }
    gP[2] += sigma;
    gP[5] -= rho;
    gQ[4] += rho;
    gQ[1] -= sigma;
    for (int i = 0; i < 6; ++i) {
      gK2[i] = C * gP[i] + S * gQ[i];
      gK3[i] = C * gQ[i] - S * gP[i];
    }
  }
  for (int i = 0; i < 3; ++i) gK1[i] = h * gpsi[i] - aB * rho * t[i];
  gK1[1] += psi * gh[1];
  gK1[2] += psi * gh[2];
  gK1[3] = 0.0;
  gK1[4] = psi * gh[4];
  gK1[5] = psi * gh[5];
  // dK1/dalpha = 1/n, dK2/dtheta = K3, dK3/dtheta = -K2
  const double cE = W * s.ea * eps, c1 = W * s.gj * r1, c2 = W * s.ei2 * r2, c3 = W * s.ei3 * r3;
  for (int i = 0; i < 6; ++i) g[i] = c1 * gK1[i] + c2 * gK2[i] + c3 * gK3[i];
  for (int i = 0; i < 3; ++i) g[i] += cE * a[i] * ij2;
  const double gth = c2 * K3 - c3 * K2;
  g[6] = gth;
  g[7] = c1 * invn + xi * gth;
  if (!WithH) return true;

  // Gauss-Newton part over x: W [EA ge ge^T + GJ gK1 gK1^T + EI2 gK2 gK2^T + EI3 gK3 gK3^T]
  const double w1 = W * s.gj, w2 = W * s.ei2, w3 = W * s.ei3, wE = W * s.ea * ij2 * ij2;
  for (int i = 0; i < 6; ++i) {
    const double x1 = w1 * gK1[i], x2 = w2 * gK2[i], x3 = w3 * gK3[i];
    for (int j = i; j < 6; ++j) H[i][j] = x1 * gK1[j] + x2 * gK2[j] + x3 * gK3[j];
    // theta and alpha columns (GN + second derivatives)
    const double hth = x2 * K3 - x3 * K2 + c2 * gK3[i] - c3 * gK2[i];
    const double hal = x1 * invn - (i < 3 ? c1 * rho * t[i] : 0.0);
    H[i][6] = hth;
    H[i][7] = hal + xi * hth;
  }
  const double hthth = w2 * K3 * K3 + w3 * K2 * K2 - (c2 * K2 + c3 * K3);
  H[6][6] = hthth;
  H[6][7] = xi * hthth;
  H[7][7] = w1 * rho + xi * xi * hthth;
  // second-derivative part over x: lt Hess(tau + aB/n) + lP Hess(P) + lQ Hess(Q) + EA eps Hess(eps)
  const double lt = c1, lP = c2 * C - c3 * S, lQ = c2 * S + c3 * C;
  const double ms = lP * a[2] - lQ * a[1], mr = lQ * b[1] - lP * b[2];
  // symmetric rank-2 part X + X^T, X = lt gh gpsi^T + ms gB gchi^T + vs gsig^T + vr grho^T,
  // vs = lP e_a2 - lQ e_a1, vr = lQ e_b1 - lP e_b2. X has nonzero columns 0..2 and rows 1, 2 (all
  // columns).
  double X[6][3];
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 3; ++j) X[i][j] = lt * gh[i] * gpsi[j] + ms * gB[i] * gchi[j];
  for (int j = 0; j < 3; ++j) {
    X[1][j] -= lQ * gsig[j];
    X[2][j] += lP * gsig[j];
    X[4][j] += lQ * grho[j];
    X[5][j] -= lP * grho[j];
  }
  // aa block: X + X^T + cI I + ctt t t^T + cww w w^T + A2 g2 g2^T + A3 g3 g3^T (+ EA terms)
  const double A2 = lt * h * psi, A3 = ms * B * chi;
  const double in3 = rho * invn, nd = invn * invd, rr = rho * rho, msb = ms * chi * b[0] * invn;
  const double cI = -(2.0 * A2 + 3.0 * A3) * rho - (A2 + A3) * nd + msb - 2.0 * mr * rr -
                    lt * aB * in3 + cE * ij2;
  const double ctt =
      (4.0 * A2 + 6.0 * A3) * rho + (A2 + A3) * nd - msb + 8.0 * mr * rr + 3.0 * lt * aB * in3;
  const double cww = (A2 + A3) * invd * invd;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      H[i][j] += X[i][j] + X[j][i] + ctt * t[i] * t[j] + cww * w[i] * w[j] + A2 * g2[i] * g2[j] +
                 A3 * g3[i] * g3[j] + wE * a[i] * a[j];
  for (int i = 0; i < 3; ++i) H[i][i] += cI;
  // ab block: X^T + rows 1,2 of vs gsig^T + ms chi (t_i delta_j0 + delta_ij) + lt psi ([i=2,j=1] -
  // [i=1,j=2])
  const double msp = ms * chi, ltp = lt * psi;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[i][3 + j] += X[3 + j][i];
  for (int j = 3; j < 6; ++j) {
    H[1][j] -= lQ * gsig[j];
    H[2][j] += lP * gsig[j];
  }
  for (int i = 0; i < 3; ++i) {
    H[i][3] += msp * t[i];
    H[i][3 + i] += msp;
  }
  H[2][4] += ltp;
  H[1][5] -= ltp;
  return true;  // upper triangle only
}

inline void fill_nan(double* p, int n) {
  for (int i = 0; i < n; ++i) p[i] = nan_value();
}

// Values of the nodal triads and alpha_B for element coordinates e.
struct ElemValues {
  double tA[3], uA[3], vA[3], m1A[3], m2A[3], tB[3], uB[3], vB[3], m1B[3], m2B[3];
  double alphaB;
  double align;  // smallest 1 + a.b of the three nodal smallest rotations
};

inline void elem_values(const ElementInput& in, const double* e, ElemValues& v) {
  const double pa = triad_value(in.tref_a, in.m1ref_a, e + 3, e[6], v.tA, v.uA, v.vA, v.m1A, v.m2A);
  const double pb =
      triad_value(in.tref_b, in.m1ref_b, e + 10, e[13], v.tB, v.uB, v.vB, v.m1B, v.m2B);
  double pab = 0.0;
  const double beta = beta_value(v.tA, v.uA, v.vA, v.tB, v.uB, pab);
  v.alphaB = wrap_pi(e[13] - e[6] + beta);
  v.align = std::min(pa, std::min(pb, pab));
  if (!(v.align > kMinAlign)) v.align = std::min(v.align, 0.0);  // also catches NaN alignments
}

// r' and r'' at quadrature point q in the local frame.
inline void local_ab(const ElementInput& in, int q, const double (*pt)[3], double* a, double* b) {
  const double* c1 = in.n1 + 4 * q;
  const double* c2 = in.n2 + 4 * q;
  for (int i = 0; i < 3; ++i) {
    a[i] = c1[0] * pt[0][i] + c1[1] * pt[1][i] + c1[2] * pt[2][i] + c1[3] * pt[3][i];
    b[i] = c2[0] * pt[0][i] + c2[1] * pt[1][i] + c2[2] * pt[2][i] + c2[3] * pt[3][i];
  }
}

inline void rotate_blocks(const double* e, const double* f0, const double* f1, const double* f2,
                          double (*pt)[3]) {
  for (int k = 0; k < 4; ++k) {
    const double* p = e + kPosOff[k];
    pt[k][0] = dot3(f0, p);
    pt[k][1] = dot3(f1, p);
    pt[k][2] = dot3(f2, p);
  }
}

template <bool WithH>
inline bool element_forces(const ElementInput& in, const Stiffness& s, const double* e, double* fe,
                           double* ke) {
  // ---- per element: nodal jets, beta (alpha_B = wrap(phiB - phiA + beta)); local frame R0 = (tA,
  // uA, vA)
  FrameJet JA;
  frame_jet<WithH>(in.tref_a, in.m1ref_a, e + 3, JA);
  double tB[3], uB[3];  // node B: t and u = SR(tref_B -> tB) m1ref_B are all that is needed
  const double sB = std::sqrt(dot3(e + 10, e + 10));
  for (int i = 0; i < 3; ++i) tB[i] = e[10 + i] / sB;
  const double alB = 1.0 + dot3(in.tref_b, tB);
  {
    const double kB = dot3(tB, in.m1ref_b) / alB;
    for (int i = 0; i < 3; ++i) uB[i] = in.m1ref_b[i] - kB * (tB[i] + in.tref_b[i]);
  }
  if (!(JA.align > kMinAlign) || !(alB > kMinAlign)) return false;
  double pab = 0.0;
  const double beta = beta_value(JA.t, JA.u, JA.v, tB, uB, pab);
  if (!(pab > kMinAlign)) return false;
  double gb[6], Hb[6][6];
  beta_derivs<WithH>(JA.t, JA.s, in.tref_a, tB, sB, in.tref_b, gb, Hb);
  const double aB = wrap_pi(e[13] - e[6] + beta);
  const double* F[3] = {JA.t, JA.u, JA.v};
  const double (*dF[3])[3] = {JA.dt, JA.du, JA.dv};  // dF[i][j][m] = d F_i[j] / d rA_x[m]
  double pt[4][3];
  rotate_blocks(e, F[0], F[1], F[2], pt);

  // ---- per quadrature point: density in the local frame, mapped by the shape-function blocks
  // local variables: p~ (12), phiA (12), alpha_B (13)
  double gt[14] = {};
  alignas(64) double Ht[14][14];
  if (WithH)
    for (int i = 0; i < 14; ++i)
      for (int j = 0; j < 14; ++j) Ht[i][j] = 0.0;
  for (int q = 0; q < in.nq; ++q) {
    double a[3], b[3], f, g[8], H[8][8];
    local_ab(in, q, pt, a, b);
    const double xq = in.xi[q];
    if (!qdensity<WithH>(a, b, aB, e[6] + xq * aB, xq, in.gw[q] * in.j0[q], in.j0[q],
                         in.kref + 3 * q, s, f, g, H))
      return false;
    const double n1[4] = {in.n1[4 * q], in.n1[4 * q + 1], in.n1[4 * q + 2], in.n1[4 * q + 3]};
    const double n2[4] = {in.n2[4 * q], in.n2[4 * q + 1], in.n2[4 * q + 2], in.n2[4 * q + 3]};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) gt[3 * k + i] += n1[k] * g[i] + n2[k] * g[3 + i];
    gt[12] += g[6];
    gt[13] += g[7];
    if (WithH) {
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < i; ++j) H[i][j] = H[j][i];
      // V = H N (rows rho = a0..b2; columns 3l+j of p~, then phiA, alpha_B), Ht_row(3k+i) += n1k
      // V_i + n2k V_3+i
      double V[6][14];
      for (int r = 0; r < 6; ++r) {
        for (int l = 0; l < 4; ++l)
          for (int j = 0; j < 3; ++j) V[r][3 * l + j] = n1[l] * H[r][j] + n2[l] * H[r][3 + j];
        V[r][12] = H[r][6];
        V[r][13] = H[r][7];
      }
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i) {
          double* row = Ht[3 * k + i];
          const double* va = V[i];
          const double* vb = V[3 + i];
          for (int c = 3 * k; c < 14; ++c) row[c] += n1[k] * va[c] + n2[k] * vb[c];
        }
      Ht[12][12] += H[6][6];
      Ht[12][13] += H[6][7];
      Ht[13][13] += H[7][7];
    }
  }

  // ---- chain rule back to e (docs/rod-derivation.md 5): p_k = R0 p~_k with R0 = R0(rA_x); alpha_B
  // = alpha_B(e)
  constexpr int pmap[12] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12};
  double G[3][3];  // G_i = sum_k gt_{k,i} p_k
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      G[i][j] = gt[i] * e[j] + gt[3 + i] * e[3 + j] + gt[6 + i] * e[7 + j] + gt[9 + i] * e[10 + j];
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      fe[pmap[3 * k + j]] = F[0][j] * gt[3 * k] + F[1][j] * gt[3 * k + 1] + F[2][j] * gt[3 * k + 2];
  for (int m = 0; m < 3; ++m) {
    double acc = 0.0;
    for (int i = 0; i < 3; ++i)
      acc += dF[i][0][m] * G[i][0] + dF[i][1][m] * G[i][1] + dF[i][2][m] * G[i][2];
    fe[3 + m] += acc;
  }
  const double galpha = gt[13];  // dU/d alpha_B
  fe[6] = gt[12] - galpha;
  fe[13] = galpha;
  for (int m = 0; m < 3; ++m) {
    fe[3 + m] += galpha * gb[m];
    fe[10 + m] += galpha * gb[3 + m];
  }
  if (!WithH) return true;

  alignas(64) double K[14][14];  // assembled locally, copied to ke at the end
  // Hpp = Rblk Ht_pp Rblk^T, blockwise R X R^T (R[j][i] = F[i][j])
  alignas(64) double Hpp[12][12];
  for (int k = 0; k < 4; ++k)
    for (int l = k; l < 4; ++l) {
      double T[3][3];  // T = X R^T
      for (int i = 0; i < 3; ++i)
        for (int jj = 0; jj < 3; ++jj)
          T[i][jj] = Ht[3 * k + i][3 * l] * F[0][jj] + Ht[3 * k + i][3 * l + 1] * F[1][jj] +
                     Ht[3 * k + i][3 * l + 2] * F[2][jj];
      for (int j = 0; j < 3; ++j)
        for (int jj = 0; jj < 3; ++jj) {
          const double v = F[0][j] * T[0][jj] + F[1][j] * T[1][jj] + F[2][j] * T[2][jj];
          Hpp[3 * k + j][3 * l + jj] = v;
          Hpp[3 * l + jj][3 * k + j] = v;
        }
    }
  // E = Rblk D: E[(k,j)][m] = sum_i F_i[j] (dF_i/dx_m . p_k), the change of R0 p~_k at fixed p~_k
  double E[12][3];
  for (int k = 0; k < 4; ++k) {
    const double* p = e + kPosOff[k];
    for (int m = 0; m < 3; ++m) {
      double dd[3];
      for (int i = 0; i < 3; ++i)
        dd[i] = dF[i][0][m] * p[0] + dF[i][1][m] * p[1] + dF[i][2][m] * p[2];
      for (int j = 0; j < 3; ++j)
        E[3 * k + j][m] = F[0][j] * dd[0] + F[1][j] * dd[1] + F[2][j] * dd[2];
    }
  }
  double HE[12][3];
  for (int r = 0; r < 12; ++r) {
    double h0 = 0.0, h1 = 0.0, h2 = 0.0;
    for (int c = 0; c < 12; ++c) {
      const double x = Hpp[r][c];
      h0 += x * E[c][0];
      h1 += x * E[c][1];
      h2 += x * E[c][2];
    }
    HE[r][0] = h0;
    HE[r][1] = h1;
    HE[r][2] = h2;
  }
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 12; ++c) K[pmap[r]][pmap[c]] = Hpp[r][c];
  for (int i = 0; i < 14; ++i) K[i][6] = K[6][i] = K[i][13] = K[13][i] = 0.0;
  // H_px = HE + S1, S1[(k,j)][m] = sum_i gt_{k,i} dF_i[j]/dx_m
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 3; ++m)
      for (int j = 0; j < 3; ++j) {
        const double v = HE[3 * k + j][m] + gt[3 * k] * dF[0][j][m] + gt[3 * k + 1] * dF[1][j][m] +
                         gt[3 * k + 2] * dF[2][j][m];
        K[pmap[3 * k + j]][3 + m] += v;
        K[3 + m][pmap[3 * k + j]] += v;
      }
  // H_xx = E^T HE + sum_i d2F_i . G_i, the latter as contractions (FrameJet comment):
  //   contract_t(G0 - ku G1 - kv G2) - (G1.w) d2ku - (G2.w) d2kv - sym(2 dku (Pt G1)^T) - sym(2 dkv
  //   (Pt G2)^T)
  {
    double gc[3], C[3][3], PG1[3], PG2[3];
    for (int j = 0; j < 3; ++j) {
      gc[j] = G[0][j] - JA.ku * G[1][j] - JA.kv * G[2][j];
      PG1[j] = dot3(JA.dt[j], G[1]);
      PG2[j] = dot3(JA.dt[j], G[2]);
    }
    contract_t(gc, JA.t, JA.s, C);
    const double g1w = dot3(G[1], JA.w), g2w = dot3(G[2], JA.w);
    for (int m = 0; m < 3; ++m)
      for (int n = m; n < 3; ++n) {
        double acc = C[m][n] - g1w * JA.d2ku[m][n] - g2w * JA.d2kv[m][n] - JA.dku[m] * PG1[n] -
                     PG1[m] * JA.dku[n] - JA.dkv[m] * PG2[n] - PG2[m] * JA.dkv[n];
        for (int r = 0; r < 12; ++r) acc += E[r][m] * HE[r][n];
        K[3 + m][3 + n] += acc;
        if (n != m) K[3 + n][3 + m] += acc;
      }
  }
  // phiA (local column 12) and alpha_B (13): global position rows Rblk ht, x rows E^T (Rblk ht)
  double hae[14];
  {
    double hp[12], hq[12];
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 3; ++j) {
        hp[3 * k + j] =
            F[0][j] * Ht[3 * k][12] + F[1][j] * Ht[3 * k + 1][12] + F[2][j] * Ht[3 * k + 2][12];
        hq[3 * k + j] =
            F[0][j] * Ht[3 * k][13] + F[1][j] * Ht[3 * k + 1][13] + F[2][j] * Ht[3 * k + 2][13];
      }
    for (int r = 0; r < 12; ++r) {
      K[pmap[r]][6] += hp[r];
      K[6][pmap[r]] += hp[r];
      hae[pmap[r]] = hq[r];
    }
    for (int m = 0; m < 3; ++m) {
      double acc = 0.0, acq = 0.0;
      for (int r = 0; r < 12; ++r) {
        acc += E[r][m] * hp[r];
        acq += E[r][m] * hq[r];
      }
      K[3 + m][6] += acc;
      K[6][3 + m] += acc;
      hae[3 + m] += acq;
    }
    K[6][6] += Ht[12][12];
    hae[6] = Ht[12][13];
    hae[13] = 0.0;
  }
  // alpha_B = wrap(phiB - phiA + beta(rA_x, rB_x)):
  // K += hae ga^T + ga hae^T + Haa ga ga^T + dU/dalpha Hbeta
  const double ga[8] = {gb[0], gb[1], gb[2], -1.0, gb[3], gb[4], gb[5], 1.0};
  const double haa = Ht[13][13];
  for (int m = 0; m < 8; ++m) {
    const int j = kAlphaDof[m];
    for (int i = 0; i < 14; ++i) {
      const double v = hae[i] * ga[m];
      K[i][j] += v;
      K[j][i] += v;
    }
    for (int n = 0; n < 8; ++n) K[j][kAlphaDof[n]] += haa * ga[m] * ga[n];
  }
  constexpr int bmap[6] = {3, 4, 5, 10, 11, 12};
  for (int m = 0; m < 6; ++m)
    for (int n = 0; n < 6; ++n) K[bmap[m]][bmap[n]] += galpha * Hb[m][n];
  std::copy(&K[0][0], &K[0][0] + 196, ke);
  return true;
}

}  // namespace detail

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

// U = sum_q gw j0 1/2 [EA eps^2 + GJ (K1-K1^0)^2 + EI2 (K2-K2^0)^2 + EI3 (K3-K3^0)^2]
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
    U += 0.5 * in.gw[q] * in.j0[q] *
         (s.ea * eps * eps + s.gj * r1 * r1 + s.ei2 * r2 * r2 + s.ei3 * r3 * r3);
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

// Nodal triad for the current nodal gradient rx and twist phi (rod-math 2).
inline void nodal_triad(const double* tref, const double* m1ref, const double* rx, double phi,
                        double* t_out, double* m1_out) {
  double u[3], v[3], m2[3];
  const double p = detail::triad_value(tref, m1ref, rx, phi, t_out, u, v, m1_out, m2);
  if (!(p > kMinAlign)) {
    detail::fill_nan(t_out, 3);
    detail::fill_nan(m1_out, 3);
  }
}

namespace detail {

// A value with its derivatives with respect to the three components of r_x (forward mode);
// used only for the load stiffness of point moments (docs/rod-derivation.md 6).
struct D3 {
  double v = 0.0;
  double d[3] = {0.0, 0.0, 0.0};
};
inline D3 operator+(const D3& a, const D3& b) {
  return {a.v + b.v, {a.d[0] + b.d[0], a.d[1] + b.d[1], a.d[2] + b.d[2]}};
}
inline D3 operator-(const D3& a, const D3& b) {
  return {a.v - b.v, {a.d[0] - b.d[0], a.d[1] - b.d[1], a.d[2] - b.d[2]}};
}
inline D3 operator*(const D3& a, const D3& b) {
  D3 r{a.v * b.v, {}};
  for (int i = 0; i < 3; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
  return r;
}
inline D3 operator*(double s, const D3& a) {
  return {s * a.v, {s * a.d[0], s * a.d[1], s * a.d[2]}};
}
inline D3 operator/(const D3& a, const D3& b) {
  D3 r{a.v / b.v, {}};
  for (int i = 0; i < 3; ++i) r.d[i] = (a.d[i] - r.v * b.d[i]) / b.v;
  return r;
}
inline D3 sqrt(const D3& a) {
  D3 r{std::sqrt(a.v), {}};
  for (int i = 0; i < 3; ++i) r.d[i] = a.d[i] / (2.0 * r.v);
  return r;
}
inline double value(double x) { return x; }
inline double value(const D3& x) { return x.v; }
inline double lift(double x, double) { return x; }
inline D3 lift(double x, const D3&) { return {x, {0.0, 0.0, 0.0}}; }

// Generalized force of a moment m at a node with gradient rx and reference triad (tr, mr):
// virtual work m . dtheta with dtheta = t x dt + t (dphi + w . dt), the spin of the nodal triad
// about t including that of the smallest rotation, w . dt = du . v (docs/rod-derivation.md 6):
//   w = -(tr.v)/(1+c) mr + (t.mr)(tr.v)/(1+c)^2 tr - (t.mr)/(1+c) v,  c = tr.t,
//   g_rx = P [(m x t) + (m.t) w] / |rx|,  g_phi = m.t,  P = I - t t^T.
template <class T>
void moment_force(const double* m, const double* tr, const double* mr, const T* rx, T* g) {
  using std::sqrt;
  const T one = lift(1.0, rx[0]);
  const T n = sqrt(rx[0] * rx[0] + rx[1] * rx[1] + rx[2] * rx[2]);
  const T t[3] = {rx[0] / n, rx[1] / n, rx[2] / n};
  const T c = tr[0] * t[0] + tr[1] * t[1] + tr[2] * t[2];
  const T tm = mr[0] * t[0] + mr[1] * t[1] + mr[2] * t[2];
  const T k = tm / (one + c);
  T u[3], v[3], w[3], f[3];
  for (int i = 0; i < 3; ++i) u[i] = lift(mr[i], rx[0]) - k * (t[i] + lift(tr[i], rx[0]));
  v[0] = t[1] * u[2] - t[2] * u[1];
  v[1] = t[2] * u[0] - t[0] * u[2];
  v[2] = t[0] * u[1] - t[1] * u[0];
  const T tv = tr[0] * v[0] + tr[1] * v[1] + tr[2] * v[2];
  const T a = tv / (one + c);
  for (int i = 0; i < 3; ++i)
    w[i] = (k * a) * lift(tr[i], rx[0]) - a * lift(mr[i], rx[0]) - k * v[i];
  const T mt = m[0] * t[0] + m[1] * t[1] + m[2] * t[2];
  f[0] = m[1] * t[2] - m[2] * t[1] + mt * w[0];
  f[1] = m[2] * t[0] - m[0] * t[2] + mt * w[1];
  f[2] = m[0] * t[1] - m[1] * t[0] + mt * w[2];
  const T ft = f[0] * t[0] + f[1] * t[1] + f[2] * t[2];
  for (int i = 0; i < 3; ++i) g[i] = (f[i] - ft * t[i]) / n;
  g[3] = mt;
}

}  // namespace detail

// Point moment M at a node with gradient rx and reference triad (tref, m1ref):
// g[4] = generalized force on (r_x, phi) and, if kl, kl[4*4] = dg/d(rx, phi) (exact, forward mode;
// g does not depend on phi).  At a re-referenced node (tref = t) g = ((M x t)/|rx|, M.t).
inline void moment_load(const double* m, const double* tref, const double* m1ref, const double* rx,
                        double* g, double* kl) {
  if (!kl) {
    detail::moment_force(m, tref, m1ref, rx, g);
    return;
  }
  detail::D3 x[3], gd[4];
  for (int i = 0; i < 3; ++i) {
    x[i].v = rx[i];
    x[i].d[i] = 1.0;
  }
  detail::moment_force(m, tref, m1ref, x, gd);
  for (int i = 0; i < 4; ++i) {
    g[i] = gd[i].v;
    for (int j = 0; j < 3; ++j) kl[4 * i + j] = gd[i].d[j];
    kl[4 * i + 3] = 0.0;
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
