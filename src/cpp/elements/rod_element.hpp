// rod_element.hpp -- one element: nodal values, the position blocks rotated into node A's frame,
// and the element force and exact tangent (the per-point density mapped by the shape functions,
// then the chain rule back to the element coordinates; docs/derivations/rod-kernel.md sections 0
// and 5). Part of the rod kernel (rod_kernel.hpp).
#ifndef RANCF_ROD_ELEMENT_HPP
#define RANCF_ROD_ELEMENT_HPP

#include <algorithm>
#include <cmath>

#include "elements/rod_common.hpp"
#include "elements/rod_density.hpp"
#include "elements/rod_frames.hpp"

namespace rancf::rod::detail {

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

// The tangent part of element_chain: ke from the local Hessian Ht, the local gradient gt, its
// contraction G with the positions and beta's derivatives gb, Hb (docs/derivations/rod-kernel.md
// 5): the position blocks rotated by R0, the frame's derivatives, phiA and alpha_B.
inline void chain_hessian(const double* e, const FrameJet& JA, const double (&Ht)[14][14],
                          const double (&gt)[14], const double (&G)[3][3], const double (&gb)[6],
                          const double (&Hb)[6][6], double* ke) {
  constexpr int pmap[12] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12};
  const double* F[3] = {JA.t, JA.u, JA.v};
  const double (*dF[3])[3] = {JA.dt, JA.du, JA.dv};  // dF[i][j][m] = d F_i[j] / d rA_x[m]
  const double galpha = gt[13];                      // dU/d alpha_B
  alignas(64) double K[14][14];                      // assembled locally, copied to ke at the end
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
}

// The element gradient fe = dPhi/de and (WithH) Hessian ke of Phi(e) = sum_q phi_q(x_q(e)), the
// per-point function given in node A's frame by density(q, a, b, alpha_B, theta, xi, g, H)
// (gradient g[8], Hessian H[8][8] upper triangle, in x = (a~, b~, phiA, alpha_B); false: not
// evaluable), mapped by the shape functions and the chain rule (docs/derivations/rod-kernel.md 0,
// 5). The elastic forces are this with the energy density (element_forces); the strain-rate
// damping uses it with single strain measures (rod_damping.hpp).
template <bool WithH, class Density>
inline bool element_chain(const ElementInput& in, const double* e, Density&& density, double* fe,
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
    double a[3], b[3], g[8], H[8][8];
    local_ab(in, q, pt, a, b);
    const double xq = in.xi[q];
    if (!density(q, a, b, aB, e[6] + xq * aB, xq, g, H)) return false;
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

  // ---- chain rule back to e (docs/derivations/rod-kernel.md 5): p_k = R0 p~_k with R0 = R0(rA_x);
  // alpha_B = alpha_B(e)
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

  chain_hessian(e, JA, Ht, gt, G, gb, Hb, ke);
  return true;
}

// Elastic force fe = dU/de and (WithH) tangent ke = d2U/de2 of the element.
template <bool WithH>
inline bool element_forces(const ElementInput& in, const Stiffness& s, const double* e, double* fe,
                           double* ke) {
  const auto energy = [&](int q, const double* a, const double* b, double aB, double th, double xq,
                          double* g, double (*H)[8]) {
    double f;
    return qdensity<WithH>(a, b, aB, th, xq, in.gw[q] * in.j0[q], in.j0[q], in.kref + 3 * q, s, f,
                           g, H);
  };
  return element_chain<WithH>(in, e, energy, fe, ke);
}

}  // namespace rancf::rod::detail

#endif  // RANCF_ROD_ELEMENT_HPP
