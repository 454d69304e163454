// ANCF / RANCF cable elements, planar and spatial (docs/derivations/cable.md §3, §6).
//
// With a = r'(xi), b = r''(xi) at a Gauss point and the reference a0 (J0 = |a0|, s0 = J0^2):
//   eps   = (a.a - s0) / (2 s0)                     Green-Lagrange axial strain (or, with
//                                                   Stiffness::engineering, |a|/J0 - 1)
//   kappa = (a x b)_z / |a|^3                       planar, signed
//   u     = kappa^2 = |a x b|^2 / |a|^6              spatial
//   W     = 1/2 [EA eps^2 + EI (kappa - kappa0)^2] J0                 planar
//   W     = 1/2 EA eps^2 J0 + 1/2 EI u J0                             spatial, straight reference
//   W     = 1/2 EA eps^2 J0 + 1/2 EI (1 + eta^2)(kr - kr0)^2 J0       spatial, curved reference
// with kr = sqrt(u + eta^2 kappa0^2), kr0 = kappa0 sqrt(1 + eta^2) (regularized magnitude
// curvature: the linearization of |kappa| at the reference, smooth where |kappa| has a cusp).
// The gradient g = dW/dz and Hessian h = d2W/dz2, z = (a, b), are hand-derived; element forces
// and tangents follow from da/de_k = N'_k I, db/de_k = N''_k I and the Gauss rule.
#include "cable.hpp"

#include <cmath>

#include "registry.hpp"

namespace rancf {
namespace {

// The axial part of the density at a Gauss point: W_a = 1/2 EA e^2 J0 with e the Green-Lagrange
// strain (aa - s0) / (2 s0) or, with st.engineering, the engineering strain lambda - 1 (lambda =
// sqrt(aa / s0)); its gradient is fe a and its Hessian eaj a a^T + fe I in a = r'
// (docs/derivations/cable.md section 6): Green-Lagrange fe = EA J0 eps / s0, eaj = EA J0 / s0^2;
// engineering fe = EA J0 (1 - 1/lambda) / s0, eaj = EA J0 / (lambda^3 s0^2).
struct Axial {
  double fe, eaj, w;
};

inline Axial axial_terms(const Stiffness& st, double aa, double s0, double j0) {
  if (!st.engineering) {
    const double eps = green_lagrange(aa, s0);
    return {st.ea * j0 * eps / s0, st.ea * j0 / (s0 * s0), 0.5 * st.ea * eps * eps * j0};
  }
  const double lam = std::sqrt(aa / s0), e = lam - 1.0;
  return {st.ea * j0 * e / (lam * s0), st.ea * j0 / (lam * lam * lam * s0 * s0),
          0.5 * st.ea * e * e * j0};
}

// Planar density: gradient g (4) and, if h, Hessian h (4 x 4) in z = (a0, a1, b0, b1).
inline void density_2d(const double* a, const double* b, double s0, double k0, double j0,
                       const Stiffness& st, double* g, double (*h)[4]) {
  const double a0 = a[0], a1 = a[1], b0 = b[0], b1 = b[1];
  const double aa = a0 * a0 + a1 * a1;
  const double inv = 1.0 / aa;
  const double p = inv / std::sqrt(aa);  // |a|^-3
  const double q25 = -3.0 * p * inv;     // dp/da_i = q25 a_i
  const Axial ax = axial_terms(st, aa, s0, j0);
  const double fe = ax.fe;
  const double c = a0 * b1 - a1 * b0;
  const double delta = c * p - k0;
  const double ca0 = b1, ca1 = -b0, cb0 = -a1, cb1 = a0;
  const double pa0 = q25 * a0, pa1 = q25 * a1;
  const double ka0 = p * ca0 + c * pa0, ka1 = p * ca1 + c * pa1;
  const double kb0 = p * cb0, kb1 = p * cb1;
  const double f = st.ei * j0 * delta;
  g[0] = fe * a0 + f * ka0;
  g[1] = fe * a1 + f * ka1;
  g[2] = f * kb0;
  g[3] = f * kb1;
  if (h == nullptr) return;
  const double s = st.ei * j0;
  const double q35 = 15.0 * p * inv * inv;
  const double eaj = ax.eaj;
  const double sd = s * delta;
  const double paa00 = q25 + q35 * a0 * a0, paa01 = q35 * a0 * a1, paa11 = q25 + q35 * a1 * a1;
  h[0][0] = eaj * a0 * a0 + fe + s * ka0 * ka0 + sd * (2.0 * ca0 * pa0 + c * paa00);
  h[0][1] = eaj * a0 * a1 + s * ka0 * ka1 + sd * (ca0 * pa1 + pa0 * ca1 + c * paa01);
  h[1][1] = eaj * a1 * a1 + fe + s * ka1 * ka1 + sd * (2.0 * ca1 * pa1 + c * paa11);
  h[1][0] = h[0][1];
  // a-b block: k_ab = p [[0, 1], [-1, 0]] + p_a c_b^T
  h[0][2] = s * ka0 * kb0 + sd * (pa0 * cb0);
  h[0][3] = s * ka0 * kb1 + sd * (p + pa0 * cb1);
  h[1][2] = s * ka1 * kb0 + sd * (-p + pa1 * cb0);
  h[1][3] = s * ka1 * kb1 + sd * (pa1 * cb1);
  h[2][0] = h[0][2];
  h[3][0] = h[0][3];
  h[2][1] = h[1][2];
  h[3][1] = h[1][3];
  h[2][2] = s * kb0 * kb0;
  h[2][3] = s * kb0 * kb1;
  h[3][2] = h[2][3];
  h[3][3] = s * kb1 * kb1;
}

// Spatial density: gradient g (6) and, if h, Hessian h (6 x 6) in z = (a, b).
inline void density_3d(const double* a, const double* b, double s0, double k0, double j0, double qr,
                       const Stiffness& st, double* g, double (*h)[6]) {
  const double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const Axial ax = axial_terms(st, aa, s0, j0);
  const double fe = ax.fe;
  const double c0 = a[1] * b[2] - a[2] * b[1];
  const double c1 = a[2] * b[0] - a[0] * b[2];
  const double c2 = a[0] * b[1] - a[1] * b[0];
  const double q = c0 * c0 + c1 * c1 + c2 * c2;
  const double ia = 1.0 / aa;
  const double sx = ia * ia * ia;  // |a|^-6
  const double u = q * sx;
  const bool curved = qr > 0.0;
  const double half = 0.5 * st.ei * j0 * (curved ? 1.0 + kCableEta * kCableEta : 1.0);
  double ratio = 0.0, h2 = 0.0;
  if (curved) {
    const double kr2 = u + qr;
    ratio = k0 * std::sqrt(1.0 + kCableEta * kCableEta) / std::sqrt(kr2);
    h2 = half * ratio / (2.0 * kr2);
  }
  const double h1 = half * (1.0 - ratio);
  const double s4 = -6.0 * sx * ia;  // d|a|^-6/da_i = s4 a_i
  double qa[3], qb[3], sa[3], ua[3], ub[3];
  for (int i = 0; i < 3; ++i) {
    qa[i] = 2.0 * bb * a[i] - 2.0 * ab * b[i];
    qb[i] = 2.0 * aa * b[i] - 2.0 * ab * a[i];
    sa[i] = s4 * a[i];
    ua[i] = qa[i] * sx + q * sa[i];
    ub[i] = qb[i] * sx;
    g[i] = fe * a[i] + h1 * ua[i];
    g[3 + i] = h1 * ub[i];
  }
  if (h == nullptr) return;
  const double s5 = 48.0 * sx * ia * ia;
  const double eaj = ax.eaj;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double eye = i == j ? 1.0 : 0.0;
      const double qaa = 2.0 * bb * eye - 2.0 * b[i] * b[j];
      const double qbb = 2.0 * aa * eye - 2.0 * a[i] * a[j];
      const double qab = 4.0 * a[i] * b[j] - 2.0 * b[i] * a[j] - 2.0 * ab * eye;
      const double saa = s4 * eye + s5 * a[i] * a[j];
      const double uaa = qaa * sx + qa[i] * sa[j] + sa[i] * qa[j] + q * saa;
      const double uab = qab * sx + sa[i] * qb[j];
      const double ubb = qbb * sx;
      h[i][j] = eaj * a[i] * a[j] + fe * eye + h1 * uaa + h2 * ua[i] * ua[j];
      h[i][3 + j] = h1 * uab + h2 * ua[i] * ub[j];
      h[3 + j][i] = h[i][3 + j];
      h[3 + i][3 + j] = h1 * ubb + h2 * ub[i] * ub[j];
    }
  }
}

// a = r'(xi) = sum_k p_k e_k and b = r''(xi) = sum_k r_k e_k at one Gauss point.
template <int D>
inline void gather_ab(const double* p, const double* r, const double* e, double* a, double* b) {
  for (int i = 0; i < D; ++i) {
    a[i] = p[0] * e[i] + p[1] * e[D + i] + p[2] * e[2 * D + i] + p[3] * e[3 * D + i];
    b[i] = r[0] * e[i] + r[1] * e[D + i] + r[2] * e[2 * D + i] + r[3] * e[3 * D + i];
  }
}

// Element forces and (optionally) tangent, dimension D; node block k of e holds e[k D + i].
template <int D>
void cable_forces(const Model& m, int el, const double* e, double* fe, double* ke) {
  constexpr int N = 4 * D;
  const CableData& c = m.cable;
  for (int i = 0; i < N; ++i) fe[i] = 0.0;
  if (ke != nullptr)
    for (int i = 0; i < N * N; ++i) ke[i] = 0.0;
  double a[D], b[D], g[2 * D], h[2 * D][2 * D];
  for (int q = 0; q < c.n_qp; ++q) {
    const int k = el * c.n_qp + q;
    const double* p = c.n1 + 4 * k;
    const double* r = c.n2 + 4 * k;
    gather_ab<D>(p, r, e, a, b);
    if constexpr (D == 2)
      density_2d(a, b, c.s0[k], c.k0[k], c.j0[k], m.stiffness, g, ke != nullptr ? h : nullptr);
    else
      density_3d(a, b, c.s0[k], c.k0[k], c.j0[k], c.qr[k], m.stiffness, g,
                 ke != nullptr ? h : nullptr);
    const double w = c.gw[q];
    for (int kk = 0; kk < 4; ++kk)
      for (int i = 0; i < D; ++i) fe[kk * D + i] += w * (p[kk] * g[i] + r[kk] * g[D + i]);
    if (ke == nullptr) continue;
    // K(kk i, l j) += X_kk(i, j) p_l + Y_kk(i, j) r_l with X_kk = w (p_kk h_aa + r_kk h_ba),
    // Y_kk = w (p_kk h_ab + r_kk h_bb): the upper block triangle
    for (int kk = 0; kk < 4; ++kk) {
      const double wp = w * p[kk], wr = w * r[kk];
      double x[D][D], y[D][D];
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) {
          x[i][j] = wp * h[i][j] + wr * h[D + i][j];
          y[i][j] = wp * h[i][D + j] + wr * h[D + i][D + j];
        }
      for (int l = kk; l < 4; ++l)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j)
            ke[(kk * D + i) * N + l * D + j] += x[i][j] * p[l] + y[i][j] * r[l];
    }
  }
  if (ke == nullptr) return;
  for (int kk = 0; kk < 4; ++kk)  // lower block triangle from the upper one (K symmetric)
    for (int l = kk + 1; l < 4; ++l)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
          ke[(l * D + j) * N + kk * D + i] = ke[(kk * D + i) * N + l * D + j];
}

template <int D>
double cable_energy(const Model& m, int el, const double* e) {
  const CableData& c = m.cable;
  const Stiffness& st = m.stiffness;
  double total = 0.0;
  double a[D], b[D];
  for (int q = 0; q < c.n_qp; ++q) {
    const int k = el * c.n_qp + q;
    const double* p = c.n1 + 4 * k;
    const double* r = c.n2 + 4 * k;
    gather_ab<D>(p, r, e, a, b);
    const QpGeometry geo = cable_qp_geometry(a, b, D);
    const double axial = axial_terms(st, geo.aa, c.s0[k], c.j0[k]).w;
    double bend;
    if constexpr (D == 2) {
      bend = (geo.kappa - c.k0[k]) * (geo.kappa - c.k0[k]);
    } else if (c.qr[k] > 0.0) {
      const double f = 1.0 + kCableEta * kCableEta;
      const double kr = std::sqrt(geo.kappa * geo.kappa + c.qr[k]);
      bend = f * (kr - c.k0[k] * std::sqrt(f)) * (kr - c.k0[k] * std::sqrt(f));
    } else {
      bend = geo.kappa * geo.kappa;
    }
    total += c.gw[q] * (axial + 0.5 * st.ei * bend * c.j0[k]);
  }
  return total;
}

}  // namespace

QpGeometry cable_qp_geometry(const double* a, const double* b, int dim) {
  QpGeometry out{};
  if (dim == 2) {
    out.aa = a[0] * a[0] + a[1] * a[1];
    out.kappa = (a[0] * b[1] - a[1] * b[0]) / (out.aa * std::sqrt(out.aa));
    return out;
  }
  out.aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const double c0 = a[1] * b[2] - a[2] * b[1];
  const double c1 = a[2] * b[0] - a[0] * b[2];
  const double c2 = a[0] * b[1] - a[1] * b[0];
  out.kappa = std::sqrt(c0 * c0 + c1 * c1 + c2 * c2) / (out.aa * std::sqrt(out.aa));
  return out;
}

const ElementKernel cable2d_kernel = {cable_forces<2>, cable_energy<2>};
const ElementKernel cable3d_kernel = {cable_forces<3>, cable_energy<3>};

}  // namespace rancf
