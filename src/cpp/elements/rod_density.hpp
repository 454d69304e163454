// rod_density.hpp -- material curvatures and the strain-energy density at one quadrature point,
// written in node A's frame, with its gradient and 8x8 Hessian (docs/derivations/rod-kernel.md
// sections 3 and 4). Part of the rod kernel (rod_kernel.hpp).
#ifndef RANCF_ROD_DENSITY_HPP
#define RANCF_ROD_DENSITY_HPP

#include <cmath>

#include "elements/rod_common.hpp"

namespace rancf::rod::detail {

// ---------------------------------------------------------------------------------------------------------
// Material curvatures at a quadrature point (docs/derivations/rod-kernel.md 3). Local frame: node
// A's triad at phiA = 0, (tA, uA, vA); a = r', b = r'' in that frame; the twist angle of the
// material triad at xi about the transported frame is theta = phiA + xi alpha_B:
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

// The section-force coefficients of a quadrature point's density in the strain measures
// m = (eps, K1, K2, K3): "stresses" cE, c1, c2, c3 (dDensity/dm) and Gauss-Newton weights wE,
// w1, w2, w3 (d2Density/dm2), all times W = gw j0.  Elastic: c = W k (m - m0), w = W k
// (qdensity); one measure alone: c = 1 for it, w = 0 (its gradient and Hessian; rod_damping.hpp).
struct Coef {
  double cE, c1, c2, c3, wE, w1, w2, w3;
};

// Gradient g[8] and (if WithH) Hessian H[8][8] (upper triangle) in the variables (a0, a1, a2, b0,
// b1, b2, phiA, alpha_B) of sum_m c_m m + 1/2 sum_m w_m (dm)^2, i.e. g = sum c_m grad m and
// H = sum_m (w_m grad m grad m^T + c_m Hess m) (docs/derivations/rod-kernel.md 4), with the
// coefficients coef(eps, K) (Coef) of the point's measures. th = phiA + xi alpha_B.
template <bool WithH, class CoefFn>
inline bool qterms(const double* ain, const double* bin, double aB, double th, double xi, double j0,
                   CoefFn&& coef, double* g, double (*H)[8]) {
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
  const double Km[3] = {K1, K2, K3};
  const Coef k = coef(eps, Km);

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
  const double cE = k.cE, c1 = k.c1, c2 = k.c2, c3 = k.c3;
  for (int i = 0; i < 6; ++i) g[i] = c1 * gK1[i] + c2 * gK2[i] + c3 * gK3[i];
  for (int i = 0; i < 3; ++i) g[i] += cE * a[i] * ij2;
  const double gth = c2 * K3 - c3 * K2;
  g[6] = gth;
  g[7] = c1 * invn + xi * gth;
  if (!WithH) return true;

  // Gauss-Newton part over x: W [EA ge ge^T + GJ gK1 gK1^T + EI2 gK2 gK2^T + EI3 gK3 gK3^T]
  const double w1 = k.w1, w2 = k.w2, w3 = k.w3, wE = k.wE * ij2 * ij2;
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

// Energy density f (times W = gw j0), its gradient g[8] and (if WithH) Hessian H[8][8] (upper
// triangle) in the variables (a0, a1, a2, b0, b1, b2, phiA, alpha_B)
// (docs/derivations/rod-kernel.md 4). th = phiA + xi alpha_B.
template <bool WithH>
inline bool qdensity(const double* a, const double* b, double aB, double th, double xi, double W,
                     double j0, const double* k0, const Stiffness& s, double& f, double* g,
                     double (*H)[8]) {
  const auto elastic = [&](double eps, const double* K) {
    const double r1 = K[0] - k0[0], r2 = K[1] - k0[1], r3 = K[2] - k0[2];
    const AxialDensity ax = axial_density(s, eps);
    f = W * (ax.w + 0.5 * (s.gj * r1 * r1 + s.ei2 * r2 * r2 + s.ei3 * r3 * r3));
    return Coef{W * ax.dw,  W * s.gj * r1, W * s.ei2 * r2, W * s.ei3 * r3,
                W * ax.ddw, W * s.gj,      W * s.ei2,      W * s.ei3};
  };
  return qterms<WithH>(a, b, aB, th, xi, j0, elastic, g, H);
}

}  // namespace rancf::rod::detail

#endif  // RANCF_ROD_DENSITY_HPP
