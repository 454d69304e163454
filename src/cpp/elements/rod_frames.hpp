// rod_frames.hpp -- nodal triads by smallest rotations (values, and node A's transported frame with
// its derivatives) and the relative twist alpha_B = wrap(phiB - phiA + beta) with the closed-form
// gradient and Hessian of beta (docs/derivations/rod-kernel.md sections 1 and 2). Part of the rod
// kernel (rod_kernel.hpp).
#ifndef RANCF_ROD_FRAMES_HPP
#define RANCF_ROD_FRAMES_HPP

#include <cmath>

#include "elements/rod_common.hpp"

namespace rancf::rod::detail {

// ---------------------------------------------------------------------------------------------------------
// Nodal triad, values only (docs/derivations/rod.md section 2, docs/derivations/rod-kernel.md 1).
// Returns 1 + tref.t (the SR alignment).
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
// scalar ingredients of the second derivatives (docs/derivations/rod-kernel.md 1). dt[i][j] = d t_i
// / d x_j
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
// Relative twist (docs/derivations/rod.md 3, docs/derivations/rod-kernel.md 2). With m1_N =
// R_{t_N}(phi_N) u_N (rotation about t_N) and SR(tA -> tB) R_{tA}(phiA) = R_{tB}(phiA) SR(tA ->
// tB):
//   alpha_B = wrap(phiB - phiA + beta),  beta = atan2(Y, X) = angle about tB from SR(tA -> tB) uA
//   to uB, X = uB.uA - (tB.uA)(uB.tA)/(1 + tA.tB),  Y = uB.vA - (tB.vA)(uB.tA)/(1 + tA.tB),
// wrap() maps to [-pi, pi) (the atan2 branch of docs/derivations/rod.md 3). beta depends on (rA_x,
// rB_x) only, so the Hessian of alpha_B is the 6x6 Hessian of beta.
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

// Gradient and Hessian of beta (docs/derivations/rod-kernel.md 2). beta depends on the nodal
// tangents only. With the twist vector of a smallest rotation, V(t, r) = (t x r)/(1 + r.t), the
// first variation is
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

}  // namespace rancf::rod::detail

#endif  // RANCF_ROD_FRAMES_HPP
