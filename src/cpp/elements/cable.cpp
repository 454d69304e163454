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
//
// Kelvin-Voigt strain-rate damping (docs/derivations/strain-rate-damping.md): N = EA eps + c_a
// deps/dt, M = EI kappa + c_b dkappa/dt: force sum_m c_m m' m_z and its Jacobians (eqs. 3-5).
// The curvatures and their derivatives in z come from the elastic law's own functions
// (curvature_2d, curvature_sq_3d); the axial strain's from axial_measure, whose e d1 and d1^2 + e
// d2 are axial_terms' fe and eaj over EA J0 (written out there to keep the elastic rounding).
#include "elements/cable.hpp"

#include <cmath>

#include "bodies/sections.hpp"
#include "elements/registry.hpp"
#include "elements/strain_rate.hpp"

namespace rancf {
namespace {

// The axial strain e at a Gauss point and its derivatives in a = r': e_a = d1 a and
// e_aa = d1 I + d2 a a^T (docs/derivations/cable.md section 6): Green-Lagrange e = (aa - s0) /
// (2 s0), d1 = 1 / s0, d2 = 0; engineering (st.engineering) e = lambda - 1 with lambda =
// sqrt(aa / s0), d1 = 1 / (lambda s0), d2 = -1 / (lambda^3 s0^2)
// (docs/derivations/strain-rate-damping.md eq. 6).
struct AxialMeasure {
  double e, d1, d2;
};

inline AxialMeasure axial_measure(bool engineering, double aa, double s0) {
  if (!engineering) return {green_lagrange(aa, s0), 1.0 / s0, 0.0};
  const double lam = std::sqrt(aa / s0);
  return {lam - 1.0, 1.0 / (lam * s0), -1.0 / (lam * lam * lam * s0 * s0)};
}

// The axial part of the density at a Gauss point: W_a = 1/2 EA e^2 J0 (AxialMeasure); its
// gradient is fe a and its Hessian eaj a a^T + fe I in a = r', fe = EA J0 e d1 and eaj = EA J0
// (d1^2 + e d2): Green-Lagrange fe = EA J0 eps / s0, eaj = EA J0 / s0^2; engineering fe = EA J0
// (1 - 1/lambda) / s0, eaj = EA J0 / (lambda^3 s0^2) (written out: the rounding of the elastic
// law is kept).  A nonlinear axial law (Stiffness::axial_law): W_a = J0 w(eps) of the
// Green-Lagrange eps, fe = J0 w' / s0 and eaj = J0 w'' / s0^2 (docs/derivations/axial-law.md).
struct Axial {
  double fe, eaj, w;
};

inline Axial axial_terms(const Stiffness& st, double aa, double s0, double j0) {
  if (st.axial_law.active()) {  // the law in the Green-Lagrange strain (axial-law.md eq. 3)
    const AxialDensity d = axial_law_density(st.axial_law, green_lagrange(aa, s0));
    return {j0 * d.dw / s0, j0 * d.ddw / (s0 * s0), j0 * d.w};
  }
  if (!st.engineering) {
    const double eps = green_lagrange(aa, s0);
    return {st.ea * j0 * eps / s0, st.ea * j0 / (s0 * s0), 0.5 * st.ea * eps * eps * j0};
  }
  const double lam = std::sqrt(aa / s0), e = lam - 1.0;
  return {st.ea * j0 * e / (lam * s0), st.ea * j0 / (lam * lam * lam * s0 * s0),
          0.5 * st.ea * e * e * j0};
}

// Planar signed curvature kappa = (a x b)_z / |a|^3 with its gradient kz (4) and, if kzz, Hessian
// (4 x 4) in z = (a0, a1, b0, b1).
inline double curvature_2d(const double* a, const double* b, double* kz, double (*kzz)[4]) {
  const double a0 = a[0], a1 = a[1], b0 = b[0], b1 = b[1];
  const double aa = a0 * a0 + a1 * a1;
  const double inv = 1.0 / aa;
  const double p = inv / std::sqrt(aa);  // |a|^-3
  const double q25 = -3.0 * p * inv;     // dp/da_i = q25 a_i
  const double c = a0 * b1 - a1 * b0;
  const double ca0 = b1, ca1 = -b0, cb0 = -a1, cb1 = a0;
  const double pa0 = q25 * a0, pa1 = q25 * a1;
  kz[0] = p * ca0 + c * pa0;
  kz[1] = p * ca1 + c * pa1;
  kz[2] = p * cb0;
  kz[3] = p * cb1;
  if (kzz == nullptr) return c * p;
  const double q35 = 15.0 * p * inv * inv;
  kzz[0][0] = 2.0 * ca0 * pa0 + c * (q25 + q35 * a0 * a0);
  kzz[0][1] = ca0 * pa1 + pa0 * ca1 + c * q35 * a0 * a1;
  kzz[1][1] = 2.0 * ca1 * pa1 + c * (q25 + q35 * a1 * a1);
  kzz[0][2] = pa0 * cb0;  // a-b block: p [[0, 1], [-1, 0]] + p_a c_b^T
  kzz[0][3] = p + pa0 * cb1;
  kzz[1][2] = -p + pa1 * cb0;
  kzz[1][3] = pa1 * cb1;
  kzz[1][0] = kzz[0][1];
  kzz[2][0] = kzz[0][2];
  kzz[3][0] = kzz[0][3];
  kzz[2][1] = kzz[1][2];
  kzz[3][1] = kzz[1][3];
  kzz[2][2] = kzz[2][3] = kzz[3][2] = kzz[3][3] = 0.0;
  return c * p;
}

// Planar density: gradient g (4) and, if h, Hessian h (4 x 4) in z = (a0, a1, b0, b1).
inline void density_2d(const double* a, const double* b, double s0, double k0, double j0,
                       const Stiffness& st, double* g, double (*h)[4]) {
  const Axial ax = axial_terms(st, a[0] * a[0] + a[1] * a[1], s0, j0);
  double kz[4], kzz[4][4];
  const double kappa = curvature_2d(a, b, kz, h != nullptr ? kzz : nullptr);
  const double s = st.ei * j0, f = s * (kappa - k0);
  for (int i = 0; i < 4; ++i) g[i] = f * kz[i];
  g[0] += ax.fe * a[0];
  g[1] += ax.fe * a[1];
  if (h == nullptr) return;
  for (int i = 0; i < 4; ++i)  // the upper triangle, mirrored
    for (int j = i; j < 4; ++j) {
      const double axial = i < 2 && j < 2 ? ax.eaj * a[i] * a[j] + (i == j ? ax.fe : 0.0) : 0.0;
      h[i][j] = axial + s * kz[i] * kz[j] + f * kzz[i][j];
      h[j][i] = h[i][j];
    }
}

// Spatial squared curvature u = kappa^2 = |a x b|^2 / |a|^6 with its gradient uz (6) and, if uzz,
// Hessian (6 x 6) in z = (a, b).
inline double curvature_sq_3d(const double* a, const double* b, double* uz, double (*uzz)[6]) {
  const double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double c0 = a[1] * b[2] - a[2] * b[1];
  const double c1 = a[2] * b[0] - a[0] * b[2];
  const double c2 = a[0] * b[1] - a[1] * b[0];
  const double q = c0 * c0 + c1 * c1 + c2 * c2;
  const double ia = 1.0 / aa;
  const double sx = ia * ia * ia;    // |a|^-6
  const double s4 = -6.0 * sx * ia;  // d|a|^-6/da_i = s4 a_i
  double qa[3], qb[3], sa[3];
  for (int i = 0; i < 3; ++i) {
    qa[i] = 2.0 * bb * a[i] - 2.0 * ab * b[i];
    qb[i] = 2.0 * aa * b[i] - 2.0 * ab * a[i];
    sa[i] = s4 * a[i];
    uz[i] = qa[i] * sx + q * sa[i];
    uz[3 + i] = qb[i] * sx;
  }
  if (uzz == nullptr) return q * sx;
  const double s5 = 48.0 * sx * ia * ia;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double eye = i == j ? 1.0 : 0.0;
      const double qaa = 2.0 * bb * eye - 2.0 * b[i] * b[j];
      const double qbb = 2.0 * aa * eye - 2.0 * a[i] * a[j];
      const double qab = 4.0 * a[i] * b[j] - 2.0 * b[i] * a[j] - 2.0 * ab * eye;
      const double saa = s4 * eye + s5 * a[i] * a[j];
      uzz[i][j] = qaa * sx + qa[i] * sa[j] + sa[i] * qa[j] + q * saa;
      uzz[i][3 + j] = qab * sx + sa[i] * qb[j];
      uzz[3 + j][i] = uzz[i][3 + j];
      uzz[3 + i][3 + j] = qbb * sx;
    }
  return q * sx;
}

// The factor (1 + eta^2) of the regularized spatial bending law at curved reference points
// (qr > 0), 1 at straight ones.
inline double bend_factor(double qr) { return qr > 0.0 ? 1.0 + kCableEta * kCableEta : 1.0; }

// Spatial density: gradient g (6) and, if h, Hessian h (6 x 6) in z = (a, b).
inline void density_3d(const double* a, const double* b, double s0, double k0, double j0, double qr,
                       const Stiffness& st, double* g, double (*h)[6]) {
  const Axial ax = axial_terms(st, a[0] * a[0] + a[1] * a[1] + a[2] * a[2], s0, j0);
  double uz[6], uzz[6][6];
  const double u = curvature_sq_3d(a, b, uz, h != nullptr ? uzz : nullptr);
  const double half = 0.5 * st.ei * j0 * bend_factor(qr);
  double ratio = 0.0, h2 = 0.0;
  if (qr > 0.0) {
    const double kr2 = u + qr;
    ratio = k0 * std::sqrt(1.0 + kCableEta * kCableEta) / std::sqrt(kr2);
    h2 = half * ratio / (2.0 * kr2);
  }
  const double h1 = half * (1.0 - ratio);
  for (int i = 0; i < 6; ++i) g[i] = h1 * uz[i];
  for (int i = 0; i < 3; ++i) g[i] += ax.fe * a[i];
  if (h == nullptr) return;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double eye = i == j ? 1.0 : 0.0;
      h[i][j] = ax.eaj * a[i] * a[j] + ax.fe * eye + h1 * uzz[i][j] + h2 * uz[i] * uz[j];
      h[i][3 + j] = h1 * uzz[i][3 + j] + h2 * uz[i] * uz[3 + j];
      h[3 + j][i] = h[i][3 + j];
      h[3 + i][3 + j] = h1 * uzz[3 + i][3 + j] + h2 * uz[3 + i] * uz[3 + j];
    }
}

// ---- Kelvin-Voigt strain-rate damping (docs/derivations/strain-rate-damping.md)

// The axial strain's gradient mz and Hessian mzz in z = (a, b) (2 D values; AxialMeasure).
template <int D>
inline void axial_z(bool engineering, const double* a, double s0, double* mz,
                    double (*mzz)[2 * D]) {
  double aa = 0.0;
  for (int i = 0; i < D; ++i) aa += a[i] * a[i];
  const AxialMeasure m = axial_measure(engineering, aa, s0);
  for (int i = 0; i < 2 * D; ++i) {
    mz[i] = i < D ? m.d1 * a[i] : 0.0;
    for (int j = 0; j < 2 * D; ++j)
      mzz[i][j] = i < D && j < D ? m.d2 * a[i] * a[j] + (i == j ? m.d1 : 0.0) : 0.0;
  }
}

// The bending measure's gradient and Hessian in z: planar the signed curvature; spatial the
// (regularized) magnitude kr = sqrt(u + qr) of the elastic law, mz = uz / (2 kr), mzz = uzz /
// (2 kr) - uz uz^T / (4 kr^3) (eq. 7).  Returns false where it is not differentiable (a spatial
// point with kr |a| <= kCableStraight: no bending damping there).
template <int D>
inline bool bending_z(const double* a, const double* b, double qr, double* mz,
                      double (*mzz)[2 * D]) {
  if constexpr (D == 2) {
    curvature_2d(a, b, mz, mzz);
    return true;
  } else {
    double uz[6], uzz[6][6];
    const double kr = std::sqrt(curvature_sq_3d(a, b, uz, uzz) + qr);
    if (!(kr * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) > kCableStraight)) return false;
    const double i1 = 0.5 / kr, i3 = 0.25 / (kr * kr * kr);
    for (int i = 0; i < 6; ++i) {
      mz[i] = i1 * uz[i];
      for (int j = 0; j < 6; ++j) mzz[i][j] = i1 * uzz[i][j] - i3 * uz[i] * uz[j];
    }
    return true;
  }
}

// The Kelvin-Voigt force of Gauss point k in z = (a, b): g (2 D) and, if jz, its Jacobian
// ck d/dz + cv d/dzd (eqs. 3-5) for the axial strain and the bending measure.
template <int D>
inline void kv_point(const Model& m, int k, const double* a, const double* b, const double* zd,
                     double ck, double cv, double* g, double (*jz)[2 * D]) {
  constexpr int Z = 2 * D;
  const Stiffness& st = m.stiffness;
  const double j0 = m.cable.j0[k];
  const double qr = D == 3 ? m.cable.qr[k] : 0.0;
  double mz[Z], mzz[Z][Z];
  if (st.damping_axial > 0.0) {
    axial_z<D>(st.engineering || st.axial_law.active(), a, m.cable.s0[k], mz, mzz);
    kv_measure<Z>(st.damping_axial * j0, mz, mzz, zd, ck, cv, g, jz);
  }
  if (st.damping_bending > 0.0 && bending_z<D>(a, b, qr, mz, mzz))
    kv_measure<Z>(st.damping_bending * j0 * bend_factor(qr), mz, mzz, zd, ck, cv, g, jz);
}

// a = r'(xi) = sum_k p_k e_k and b = r''(xi) = sum_k r_k e_k at one Gauss point.
template <int D>
inline void gather_ab(const double* p, const double* r, const double* e, double* a, double* b) {
  for (int i = 0; i < D; ++i) {
    a[i] = p[0] * e[i] + p[1] * e[D + i] + p[2] * e[2 * D + i] + p[3] * e[3 * D + i];
    b[i] = r[0] * e[i] + r[1] * e[D + i] + r[2] * e[2 * D + i] + r[3] * e[3 * D + i];
  }
}

// A Gauss point's force g and matrix h in z = (a, b), weight w, mapped onto the element: fe
// += w (p_k g_a + r_k g_b) and K(kk i, l j) += X_kk(i, j) p_l + Y_kk(i, j) r_l with X_kk = w (p_kk
// h_aa + r_kk h_ba), Y_kk = w (p_kk h_ab + r_kk h_bb); only the upper block triangle (l >= kk)
// if `upper` (h symmetric).
template <int D>
inline void map_point(double w, const double* p, const double* r, const double* g,
                      const double (*h)[2 * D], bool upper, double* fe, double* ke) {
  constexpr int N = 4 * D;
  for (int kk = 0; kk < 4; ++kk)
    for (int i = 0; i < D; ++i) fe[kk * D + i] += w * (p[kk] * g[i] + r[kk] * g[D + i]);
  if (ke == nullptr) return;
  for (int kk = 0; kk < 4; ++kk) {
    const double wp = w * p[kk], wr = w * r[kk];
    double x[D][D], y[D][D];
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        x[i][j] = wp * h[i][j] + wr * h[D + i][j];
        y[i][j] = wp * h[i][D + j] + wr * h[D + i][D + j];
      }
    for (int l = upper ? kk : 0; l < 4; ++l)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
          ke[(kk * D + i) * N + l * D + j] += x[i][j] * p[l] + y[i][j] * r[l];
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
    map_point<D>(c.gw[q], p, r, g, h, true, fe, ke);
  }
  if (ke == nullptr) return;
  for (int kk = 0; kk < 4; ++kk)  // lower block triangle from the upper one (K symmetric)
    for (int l = kk + 1; l < 4; ++l)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
          ke[(l * D + j) * N + kk * D + i] = ke[(kk * D + i) * N + l * D + j];
}

// Kelvin-Voigt damping force fe of the element at (e, ed) and, if ke, its Jacobian ck d/de + cv
// d/ded (not symmetric; docs/derivations/strain-rate-damping.md eqs. 3-5).
template <int D>
void cable_damping(const Model& m, int el, const double* e, const double* ed, double ck, double cv,
                   double* fe, double* ke) {
  constexpr int N = 4 * D, Z = 2 * D;
  const CableData& c = m.cable;
  for (int i = 0; i < N; ++i) fe[i] = 0.0;
  if (ke != nullptr)
    for (int i = 0; i < N * N; ++i) ke[i] = 0.0;
  double a[D], b[D], zd[Z];
  for (int q = 0; q < c.n_qp; ++q) {
    const int k = el * c.n_qp + q;
    const double* p = c.n1 + 4 * k;
    const double* r = c.n2 + 4 * k;
    gather_ab<D>(p, r, e, a, b);
    gather_ab<D>(p, r, ed, zd, zd + D);
    double g[Z] = {}, jz[Z][Z] = {};
    kv_point<D>(m, k, a, b, zd, ck, cv, g, ke != nullptr ? jz : nullptr);
    map_point<D>(c.gw[q], p, r, g, jz, false, fe, ke);
  }
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

const ElementKernel cable2d_kernel = {
    cable_forces<2>,      cable_energy<2>, cable_damping<2>, section_cable, 2, /*triads=*/false,
    /*centre_line=*/true, /*winch=*/true};
const ElementKernel cable3d_kernel = {
    cable_forces<3>,      cable_energy<3>, cable_damping<3>, section_cable, 2, /*triads=*/false,
    /*centre_line=*/true, /*winch=*/true};

}  // namespace rancf
