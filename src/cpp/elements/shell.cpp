// RANCF Kirchhoff-Love shell elements (shell.hpp; docs/derivations/shell.md sec. 3-6).
//
// At a Gauss point, with a_1 = r_,xi, a_2 = r_,eta, a_11, a_22, a_12 the second derivatives, the
// normal a3 = a3t / |a3t|, a3t = a_1 x a_2 (eq. 4.2), in Voigt form [11, 22, 2 12]:
//   eps = [(a_1.a_1 - A_11)/2, (a_2.a_2 - A_22)/2, a_1.a_2 - A_12]          (eq. 4.5)
//   kap = [B_11 - a_11.a3, B_22 - a_22.a3, 2 (B_12 - a_12.a3)]
//   W   = 1/2 sum_g wdA_g [t epsb_g.D_g epsb_g + t^3/12 kap_g.D_g kap_g]   (eq. 4.7)
// with epsb = P eps the projected membrane strains (eq. 5.1; P = I for "full" and "reduced"),
// P the discrete L2(dA) projection on the Gauss points of each strain component; "reduced" sums
// the membrane term on its own 3 x 3 rule.  With coordinate r = (s, d)
// (shape s, axis d) and S_s,a its shape function's derivatives, a_a,r = S_s,a e_d and (eq. 4.8)
//   eps_r = [S_s,1 a_1[d], S_s,2 a_2[d], S_s,1 a_2[d] + S_s,2 a_1[d]]
//   a3t_r = S_s,1 e_d x a_2 + S_s,2 a_1 x e_d,  at_r = a3.a3t_r,  a3_r = (a3t_r - a3 at_r) / at
//   b_ab,r = S_s,ab a3[d] + a_ab.a3_r,  kap_r = -[b_11,r, b_22,r, 2 b_12,r]
// and (eq. 4.9, r = (s, d), u = (t, e)) a3t_ru = (S_s,1 S_t,2 - S_t,1 S_s,2) e_d x e_e,
//   a3_ru = a3t_ru/at - a3t_r at_u/at^2 - a3t_u at_r/at^2 - a3 at_ru/at + 2 a3 at_r at_u/at^2,
//   at_ru = a3_u.a3t_r + a3.a3t_ru,  b_ab,ru = S_s,ab a3_u[d] + S_t,ab a3_r[e] + a_ab.a3_ru.
#include "elements/shell.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "bodies/cable_shape.hpp"
#include "bodies/threads.hpp"
#include "elements/registry.hpp"

namespace rancf {
namespace {

constexpr int kD = kShellDofs;
constexpr double kPi = 3.14159265358979323846;

std::string number(double x) {
  std::string s = std::to_string(x);
  return s.size() > 24 ? s.substr(0, 24) : s;
}

/// One line naming the field, what it allows and what it got.
[[noreturn]] void fail(const char* field, const std::string& expected, const std::string& got) {
  throw std::invalid_argument(std::string("shell.") + field + ": expected " + expected + ", got " +
                              got);
}

inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// x.D y with D the upper triangle D11 D12 D13 D22 D23 D33.
inline double dform(const double* d, const double* x, const double* y) {
  return x[0] * (d[0] * y[0] + d[1] * y[1] + d[2] * y[2]) +
         x[1] * (d[1] * y[0] + d[3] * y[1] + d[4] * y[2]) +
         x[2] * (d[2] * y[0] + d[4] * y[1] + d[5] * y[2]);
}

inline void dtimes(const double* d, const double* x, double* y) {
  y[0] = d[0] * x[0] + d[1] * x[1] + d[2] * x[2];
  y[1] = d[1] * x[0] + d[3] * x[1] + d[4] * x[2];
  y[2] = d[2] * x[0] + d[4] * x[1] + d[5] * x[2];
}

/// The surface at a Gauss point: a_1, a_2, the second derivatives (11, 22, 12), a3t, |a3t|, a3.
struct Kin {
  double a[5][3];
  double nt[3];
  double at;
  double n[3];
};

Kin kinematics(const ShellPoint& p, const double* e) {
  Kin k{};
  for (int s = 0; s < kShellShapes; ++s)
    for (int m = 0; m < 5; ++m)
      for (int d = 0; d < 3; ++d) k.a[m][d] += p.s[m + 1][s] * e[3 * s + d];
  cross(k.a[0], k.a[1], k.nt);
  k.at = std::sqrt(dot(k.nt, k.nt));
  for (int d = 0; d < 3; ++d) k.n[d] = k.nt[d] / k.at;
  return k;
}

/// Membrane strains and curvature changes (Voigt) at a Gauss point (eq. 4.5).
void strains(const Kin& k, const ShellPoint& p, double* eps, double* kap) {
  eps[0] = 0.5 * (dot(k.a[0], k.a[0]) - p.a_ref[0]);
  eps[1] = 0.5 * (dot(k.a[1], k.a[1]) - p.a_ref[1]);
  eps[2] = dot(k.a[0], k.a[1]) - p.a_ref[2];
  kap[0] = p.b_ref[0] - dot(k.a[2], k.n);
  kap[1] = p.b_ref[1] - dot(k.a[3], k.n);
  kap[2] = 2.0 * (p.b_ref[2] - dot(k.a[4], k.n));
}

/// First variations of the membrane strains at a Gauss point (eq. 4.8), 3 x 48.
struct MembraneVariations {
  double bm[3][kD];
};

void membrane_variations(const Kin& k, const ShellPoint& p, MembraneVariations& v) {
  for (int s = 0; s < kShellShapes; ++s)
    for (int d = 0; d < 3; ++d) {
      const int r = 3 * s + d;
      v.bm[0][r] = p.s[1][s] * k.a[0][d];
      v.bm[1][r] = p.s[2][s] * k.a[1][d];
      v.bm[2][r] = p.s[1][s] * k.a[1][d] + p.s[2][s] * k.a[0][d];
    }
}

/// First variations of the curvature changes at a Gauss point (eq. 4.8): bb (3 x 48), and
/// a3t_r, a3_r (48 x 3), at_r (48) for the second variation.
struct Variations {
  double bb[3][kD];
  double nt_r[kD][3], n_r[kD][3], at_r[kD];
};

void variations(const Kin& k, const ShellPoint& p, Variations& v) {
  for (int s = 0; s < kShellShapes; ++s) {
    const double s1 = p.s[1][s], s2 = p.s[2][s];
    for (int d = 0; d < 3; ++d) {
      const int r = 3 * s + d;
      double ed[3] = {0.0, 0.0, 0.0}, c1[3], c2[3];
      ed[d] = 1.0;
      cross(ed, k.a[1], c1);
      cross(k.a[0], ed, c2);
      for (int x = 0; x < 3; ++x) v.nt_r[r][x] = s1 * c1[x] + s2 * c2[x];
      v.at_r[r] = dot(k.n, v.nt_r[r]);
      for (int x = 0; x < 3; ++x) v.n_r[r][x] = (v.nt_r[r][x] - k.n[x] * v.at_r[r]) / k.at;
      v.bb[0][r] = -(p.s[3][s] * k.n[d] + dot(k.a[2], v.n_r[r]));
      v.bb[1][r] = -(p.s[4][s] * k.n[d] + dot(k.a[3], v.n_r[r]));
      v.bb[2][r] = -2.0 * (p.s[5][s] * k.n[d] + dot(k.a[4], v.n_r[r]));
    }
  }
}

/// ke += f B^T D B (B 3 x 48, D upper triangle).
void add_material(double* ke, const double (*b)[kD], const double* d, double f) {
  double db[3][kD];
  for (int r = 0; r < kD; ++r) {
    const double x[3] = {b[0][r], b[1][r], b[2][r]};
    double y[3];
    dtimes(d, x, y);
    for (int i = 0; i < 3; ++i) db[i][r] = f * y[i];
  }
  for (int r = 0; r < kD; ++r)
    for (int u = 0; u < kD; ++u)
      ke[r * kD + u] += b[0][r] * db[0][u] + b[1][r] * db[1][u] + b[2][r] * db[2][u];
}

/// ke += n . eps_ru: n[0] S_s,1 S_t,1 + n[1] S_s,2 S_t,2 + n[2] (S_s,1 S_t,2 + S_s,2 S_t,1), d = e.
void add_membrane_geometric(double* ke, const ShellPoint& p, const double* n) {
  for (int s = 0; s < kShellShapes; ++s)
    for (int t = 0; t < kShellShapes; ++t) {
      const double g = n[0] * p.s[1][s] * p.s[1][t] + n[1] * p.s[2][s] * p.s[2][t] +
                       n[2] * (p.s[1][s] * p.s[2][t] + p.s[2][s] * p.s[1][t]);
      for (int d = 0; d < 3; ++d) ke[(3 * s + d) * kD + 3 * t + d] += g;
    }
}

/// ke += f m . kap_ru = -f sum_I mm_I b_I,ru, mm = [m11, m22, 2 m12] (eq. 4.9).
void add_bending_geometric(double* ke, const ShellPoint& p, const Kin& k, const Variations& v,
                           const double* m, double f) {
  const double mm[3] = {m[0], m[1], 2.0 * m[2]};
  double bbar[3], ssum[kShellShapes], bnt[kD];
  for (int x = 0; x < 3; ++x) bbar[x] = mm[0] * k.a[2][x] + mm[1] * k.a[3][x] + mm[2] * k.a[4][x];
  for (int s = 0; s < kShellShapes; ++s)
    ssum[s] = mm[0] * p.s[3][s] + mm[1] * p.s[4][s] + mm[2] * p.s[5][s];
  for (int r = 0; r < kD; ++r) bnt[r] = dot(bbar, v.nt_r[r]);
  const double ba3 = dot(bbar, k.n), at = k.at, at2 = at * at;
  double bx[3][3] = {}, ax[3][3] = {};  // bbar.(e_d x e_e), a3.(e_d x e_e)
  for (int d = 0; d < 3; ++d) {
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
    bx[d][e1] = bbar[e2];
    bx[d][e2] = -bbar[e1];
    ax[d][e1] = k.n[e2];
    ax[d][e2] = -k.n[e1];
  }
  for (int r = 0; r < kD; ++r) {
    const int s = r / 3, d = r % 3;
    for (int u = r; u < kD; ++u) {
      const int t = u / 3, e = u % 3;
      const double c = p.s[1][s] * p.s[2][t] - p.s[1][t] * p.s[2][s];
      const double at_ru = dot(v.n_r[u], v.nt_r[r]) + c * ax[d][e];
      const double ba = c * bx[d][e] / at - (bnt[r] * v.at_r[u] + bnt[u] * v.at_r[r]) / at2 -
                        ba3 * at_ru / at + 2.0 * ba3 * v.at_r[r] * v.at_r[u] / at2;
      const double g = -f * (ssum[s] * v.n_r[u][d] + ssum[t] * v.n_r[r][e] + ba);
      ke[r * kD + u] += g;
      if (u != r) ke[u * kD + r] += g;
    }
  }
}

/// Solve the SPD system g x = b (n x n, m right-hand sides, row-major b n x m) in place.
void cholesky_solve(std::vector<double>& g, int n, std::vector<double>& b, int m) {
  for (int j = 0; j < n; ++j) {
    double s = g[j * n + j];
    for (int k = 0; k < j; ++k) s -= g[j * n + k] * g[j * n + k];
    if (!(s > 0.0))
      fail("gauss", "a rule that resolves the projection spaces", "a singular Gram matrix");
    g[j * n + j] = std::sqrt(s);
    for (int i = j + 1; i < n; ++i) {
      double t = g[i * n + j];
      for (int k = 0; k < j; ++k) t -= g[i * n + k] * g[j * n + k];
      g[i * n + j] = t / g[j * n + j];
    }
  }
  for (int c = 0; c < m; ++c) {
    for (int i = 0; i < n; ++i) {
      double t = b[i * m + c];
      for (int k = 0; k < i; ++k) t -= g[i * n + k] * b[k * m + c];
      b[i * m + c] = t / g[i * n + i];
    }
    for (int i = n - 1; i >= 0; --i) {
      double t = b[i * m + c];
      for (int k = i + 1; k < n; ++k) t -= g[k * n + i] * b[k * m + c];
      b[i * m + c] = t / g[i * n + i];
    }
  }
}

/// Legendre polynomial P_k(2 x - 1) (a well-conditioned basis of the projection spaces).
double legendre01(int k, double x) {
  const double z = 2.0 * x - 1.0;
  double p0 = 1.0, p1 = z;
  if (k == 0) return p0;
  for (int j = 2; j <= k; ++j) {
    const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

void check_values(const char* field, const std::vector<double>& v, bool positive) {
  for (const double x : v)
    if (!std::isfinite(x) || (positive && !(x > 0.0)))
      fail(field, positive ? "finite values > 0" : "finite values", number(x));
}

void check_input(const ShellInput& in) {
  const ShellMaterial& m = in.material;
  if (!(m.thickness > 0.0)) fail("thickness", "a number > 0", number(m.thickness));
  if (!(m.youngs_modulus > 0.0)) fail("youngs_modulus", "a number > 0", number(m.youngs_modulus));
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    fail("poisson_ratio", "a number in (-1, 0.5)", number(m.poisson_ratio));
  if (!(m.density >= 0.0)) fail("density", "a number >= 0", number(m.density));
  const bool projected = in.membrane == MembraneStrains::projected;
  const int lo = projected ? 4 : kReducedGauss;
  if (in.gauss < lo || in.gauss > 16)
    fail("gauss",
         std::to_string(lo) + " to 16 points per direction" +
             (projected ? " (projected membrane strains need 4)" : ""),
         std::to_string(in.gauss));
  const std::size_t ne = in.connectivity.size() / 4;
  if (ne == 0 || in.connectivity.size() != 4 * ne)
    fail("connectivity", "(n_el, 4) node indices, n_el >= 1",
         std::to_string(in.connectivity.size()) + " values");
  const std::string el = std::to_string(ne) + " elements";
  if (in.weights_u.size() != 4 * ne) fail("weights_u", "(n_el, 4) values", el);
  if (in.weights_v.size() != 4 * ne) fail("weights_v", "(n_el, 4) values", el);
  if (in.scales.size() != 2 * ne) fail("scales", "(n_el, 2) values", el);
  if (in.q0.size() != 12 * static_cast<std::size_t>(in.n_nodes))
    fail("q0", "12 values a node", std::to_string(in.q0.size()));
  for (const std::int64_t c : in.connectivity)
    if (c < 0 || c >= in.n_nodes)
      fail("connectivity", "node indices in [0, " + std::to_string(in.n_nodes) + ")",
           std::to_string(c));
  check_values("weights_u", in.weights_u, true);
  check_values("weights_v", in.weights_v, true);
  check_values("scales", in.scales, true);
  check_values("q0", in.q0, false);
}

}  // namespace

void gauss_legendre01(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 0 ? 1.0 : p1, pm = n == 1 ? 1.0 : p0;
      dp = n * (z * pn - pm) / (z * z - 1.0);
      const double dz = pn / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = 0.5 * (1.0 - z);
    w[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

ShellElements::ShellElements(ShellInput in) : in_(std::move(in)) {
  check_input(in_);
  const int gm = in_.membrane == MembraneStrains::reduced ? kReducedGauss : in_.gauss;
  n_qp_ = in_.gauss * in_.gauss;
  n_mp_ = gm * gm;
  std::vector<double> x, w, xm, wm;
  gauss_legendre01(in_.gauss, x, w);
  gauss_legendre01(gm, xm, wm);
  const auto ne = static_cast<std::size_t>(n_el());
  pts_.resize(ne * static_cast<std::size_t>(n_qp_));
  mpts_.resize(ne * static_cast<std::size_t>(n_mp_));
  proj_.assign(ne * 3 * static_cast<std::size_t>(n_mp_ * n_mp_), 0.0);
  for (int el = 0; el < n_el(); ++el) {
    set_up_points(el, x, w, pts_.data() + static_cast<std::size_t>(el * n_qp_));
    set_up_points(el, xm, wm, mpts_.data() + static_cast<std::size_t>(el * n_mp_));
    set_up_projection(el, xm);
  }
}

void ShellElements::set_up_points(int el, const std::vector<double>& x,
                                  const std::vector<double>& w, ShellPoint* out) const {
  const int ng = static_cast<int>(x.size());
  const double* wu = in_.weights_u.data() + 4 * el;
  const double* wv = in_.weights_v.data() + 4 * el;
  const double lu = in_.scales[2 * static_cast<std::size_t>(el)];
  const double lv = in_.scales[2 * static_cast<std::size_t>(el) + 1];
  double e0[kD];
  gather(el, in_.q0.data(), e0);
  const double c =
      in_.material.youngs_modulus / (1.0 - in_.material.poisson_ratio * in_.material.poisson_ratio);
  const double nu = in_.material.poisson_ratio;
  for (int q = 0; q < ng; ++q)
    for (int p = 0; p < ng; ++p) {
      double n[3][4], m[3][4];
      cable_shape(wu, lu, x[static_cast<std::size_t>(p)], n[0], n[1], n[2]);
      cable_shape(wv, lv, x[static_cast<std::size_t>(q)], m[0], m[1], m[2]);
      ShellPoint& pt = out[p + ng * q];
      static constexpr int kOrder[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {0, 2}, {1, 1}};
      for (int s = 0; s < kShellShapes; ++s) {
        const int corner = s / 4, k = s % 4;
        const int a = 2 * (corner % 2) + k % 2, b = 2 * (corner / 2) + k / 2;
        for (int o = 0; o < 6; ++o) pt.s[o][s] = n[kOrder[o][0]][a] * m[kOrder[o][1]][b];
      }
      const Kin k = kinematics(pt, e0);
      if (!(k.at > 0.0) || !std::isfinite(k.at))
        fail("q0", "a regular reference surface (|A1 x A2| > 0)",
             "a vanishing normal in element " + std::to_string(el));
      pt.w = w[static_cast<std::size_t>(p)] * w[static_cast<std::size_t>(q)];
      pt.wda = pt.w * k.at;
      pt.a_ref[0] = dot(k.a[0], k.a[0]);
      pt.a_ref[1] = dot(k.a[1], k.a[1]);
      pt.a_ref[2] = dot(k.a[0], k.a[1]);
      for (int i = 0; i < 3; ++i) pt.b_ref[i] = dot(k.a[2 + i], k.n);
      const double det = pt.a_ref[0] * pt.a_ref[1] - pt.a_ref[2] * pt.a_ref[2];
      const double g11 = pt.a_ref[1] / det, g22 = pt.a_ref[0] / det, g12 = -pt.a_ref[2] / det;
      pt.d[0] = c * g11 * g11;
      pt.d[1] = c * (nu * g11 * g22 + (1.0 - nu) * g12 * g12);
      pt.d[2] = c * g11 * g12;
      pt.d[3] = c * g22 * g22;
      pt.d[4] = c * g22 * g12;
      pt.d[5] = c * (0.5 * (1.0 - nu) * g11 * g22 + 0.5 * (1.0 + nu) * g12 * g12);
    }
}

void ShellElements::set_up_projection(int el, const std::vector<double>& x) {
  const int ng = static_cast<int>(x.size()), nq = n_mp_;
  double* pr = proj_.data() + static_cast<std::size_t>(el) * 3 * static_cast<std::size_t>(nq * nq);
  if (in_.membrane != MembraneStrains::projected) {
    for (int i = 0; i < 3; ++i)
      for (int g = 0; g < nq; ++g) pr[(i * nq + g) * nq + g] = 1.0;
    return;
  }
  static constexpr int kDeg[3][2] = {{2, 3}, {3, 2}, {2, 2}};  // eq. 5.1
  const ShellPoint* pt = membrane_points(el);
  for (int i = 0; i < 3; ++i) {
    const int du = kDeg[i][0] + 1, dv = kDeg[i][1] + 1, np = du * dv;
    std::vector<double> phi(static_cast<std::size_t>(np * nq));  // (np, nq)
    for (int g = 0; g < nq; ++g)
      for (int a = 0; a < du; ++a)
        for (int b = 0; b < dv; ++b)
          phi[static_cast<std::size_t>((a + du * b) * nq + g)] =
              legendre01(a, x[static_cast<std::size_t>(g % ng)]) *
              legendre01(b, x[static_cast<std::size_t>(g / ng)]);
    std::vector<double> gram(static_cast<std::size_t>(np * np), 0.0);
    std::vector<double> rhs(static_cast<std::size_t>(np * nq));  // Phi^T W (np, nq)
    for (int k = 0; k < np; ++k)
      for (int g = 0; g < nq; ++g) {
        const double v = phi[static_cast<std::size_t>(k * nq + g)] * pt[g].wda;
        rhs[static_cast<std::size_t>(k * nq + g)] = v;
        for (int l = 0; l < np; ++l)
          gram[static_cast<std::size_t>(k * np + l)] +=
              v * phi[static_cast<std::size_t>(l * nq + g)];
      }
    cholesky_solve(gram, np, rhs, nq);
    for (int g = 0; g < nq; ++g)
      for (int h = 0; h < nq; ++h) {
        double s = 0.0;
        for (int k = 0; k < np; ++k)
          s +=
              phi[static_cast<std::size_t>(k * nq + g)] * rhs[static_cast<std::size_t>(k * nq + h)];
        pr[(i * nq + g) * nq + h] = s;
      }
  }
}

void ShellElements::gather(int el, const double* q, double* e) const {
  for (int c = 0; c < 4; ++c) {
    const std::int64_t base = 12 * in_.connectivity[static_cast<std::size_t>(4 * el + c)];
    for (int k = 0; k < 12; ++k) e[12 * c + k] = q[base + k];
  }
}

std::vector<double> ShellElements::membrane_strains(int el, const double* e) const {
  const ShellPoint* pt = membrane_points(el);
  const double* pr = projection(el);
  const int nq = n_mp_;
  std::vector<double> eps(static_cast<std::size_t>(3 * nq)), eb(eps.size(), 0.0);
  for (int g = 0; g < nq; ++g) {
    double kap[3];
    strains(kinematics(pt[g], e), pt[g], &eps[static_cast<std::size_t>(3 * g)], kap);
  }
  for (int g = 0; g < nq; ++g)
    for (int i = 0; i < 3; ++i)
      for (int h = 0; h < nq; ++h)
        eb[static_cast<std::size_t>(3 * g + i)] +=
            pr[(i * nq + g) * nq + h] * eps[static_cast<std::size_t>(3 * h + i)];
  return eb;
}

double ShellElements::element_energy(int el, const double* e) const {
  const ShellPoint* pt = points(el);
  const ShellPoint* mp = membrane_points(el);
  const double t = in_.material.thickness, tb = t * t * t / 12.0;
  double w = 0.0;
  for (int g = 0; g < n_qp_; ++g) {
    double eps[3], kap[3];
    strains(kinematics(pt[g], e), pt[g], eps, kap);
    w += 0.5 * tb * pt[g].wda * dform(pt[g].d, kap, kap);
  }
  const std::vector<double> eb = membrane_strains(el, e);
  for (int g = 0; g < n_mp_; ++g) {
    const double* x = &eb[static_cast<std::size_t>(3 * g)];
    w += 0.5 * t * mp[g].wda * dform(mp[g].d, x, x);
  }
  return w;
}

void ShellElements::add_membrane(int el, const double* e, double* fe, double* ke) const {
  const ShellPoint* pt = membrane_points(el);
  const double* pr = projection(el);
  const int nq = n_mp_;
  const double t = in_.material.thickness;
  std::vector<MembraneVariations> var(static_cast<std::size_t>(nq));
  for (int g = 0; g < nq; ++g) membrane_variations(kinematics(pt[g], e), pt[g], var[g]);
  // epsb = P eps, nb_g = t D_g epsb_g, nt_h = sum_g P_gh wdA_g nb_g (per component)
  const std::vector<double> eb = membrane_strains(el, e);
  std::vector<double> nt(static_cast<std::size_t>(3 * nq), 0.0);
  for (int g = 0; g < nq; ++g) {
    double nb[3];
    dtimes(pt[g].d, &eb[static_cast<std::size_t>(3 * g)], nb);
    for (int i = 0; i < 3; ++i)
      for (int h = 0; h < nq; ++h)
        nt[static_cast<std::size_t>(3 * h + i)] +=
            pr[(i * nq + g) * nq + h] * t * pt[g].wda * nb[i];
  }
  for (int h = 0; h < nq; ++h) {
    const MembraneVariations& v = var[static_cast<std::size_t>(h)];
    const double* n = &nt[static_cast<std::size_t>(3 * h)];
    for (int r = 0; r < kD; ++r) fe[r] += n[0] * v.bm[0][r] + n[1] * v.bm[1][r] + n[2] * v.bm[2][r];
    if (ke != nullptr) add_membrane_geometric(ke, pt[h], n);
  }
  if (ke == nullptr) return;
  for (int g = 0; g < nq; ++g) {  // material part with the projected variations
    double bb[3][kD] = {};
    for (int i = 0; i < 3; ++i)
      for (int h = 0; h < nq; ++h) {
        const double ph = pr[(i * nq + g) * nq + h];
        if (ph == 0.0) continue;
        const double* bh = var[static_cast<std::size_t>(h)].bm[i];
        for (int r = 0; r < kD; ++r) bb[i][r] += ph * bh[r];
      }
    add_material(ke, bb, pt[g].d, t * pt[g].wda);
  }
}

void ShellElements::element_forces(int el, const double* e, double* fe, double* ke) const {
  const ShellPoint* pt = points(el);
  const double t = in_.material.thickness, tb = t * t * t / 12.0;
  std::fill(fe, fe + kD, 0.0);
  if (ke != nullptr) std::fill(ke, ke + kD * kD, 0.0);
  Variations v;
  for (int g = 0; g < n_qp_; ++g) {  // bending
    const Kin k = kinematics(pt[g], e);
    double eps[3], kap[3], m[3];
    strains(k, pt[g], eps, kap);
    variations(k, pt[g], v);
    dtimes(pt[g].d, kap, m);
    for (double& x : m) x *= tb * pt[g].wda;
    for (int r = 0; r < kD; ++r) fe[r] += m[0] * v.bb[0][r] + m[1] * v.bb[1][r] + m[2] * v.bb[2][r];
    if (ke == nullptr) continue;
    add_material(ke, v.bb, pt[g].d, tb * pt[g].wda);
    add_bending_geometric(ke, pt[g], k, v, m, 1.0);
  }
  add_membrane(el, e, fe, ke);
}

double ShellElements::energy(const double* q) const {
  double w = 0.0, e[kD];
  for (int el = 0; el < n_el(); ++el) {
    gather(el, q, e);
    w += element_energy(el, e);
  }
  return w;
}

void ShellElements::forces(const double* q, double* f) const {
  std::fill(f, f + n(), 0.0);
  double e[kD], fe[kD];
  for (int el = 0; el < n_el(); ++el) {
    gather(el, q, e);
    element_forces(el, e, fe, nullptr);
    for (int c = 0; c < 4; ++c) {
      const std::int64_t base = 12 * in_.connectivity[static_cast<std::size_t>(4 * el + c)];
      for (int k = 0; k < 12; ++k) f[base + k] += fe[12 * c + k];
    }
  }
}

namespace {

/// The model coordinates of an element's 48.
void dof_map(const std::int64_t* conn, std::int64_t* g) {
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 12; ++k) g[12 * c + k] = 12 * conn[c] + k;
}

}  // namespace

namespace {

/// The tangent's element loop in chunks of elements, each writing its elements' 2304 triplets
/// at their own place (the result does not depend on the number of threads).
struct TangentJob {
  const ShellElements* shell;
  const double* q;
  Triplets* t;
  int n_chunks;
};

void tangent_chunk(void* ctx, int chunk) {
  const auto* job = static_cast<const TangentJob*>(ctx);
  const ShellElements& s = *job->shell;
  const int lo = s.n_el() * chunk / job->n_chunks, hi = s.n_el() * (chunk + 1) / job->n_chunks;
  std::vector<double> ke(kD * kD);
  double e[kD], fe[kD];
  std::int64_t g[kD];
  for (int el = lo; el < hi; ++el) {
    s.gather(el, job->q, e);
    s.element_forces(el, e, fe, ke.data());
    dof_map(s.input().connectivity.data() + 4 * el, g);
    const std::size_t at = static_cast<std::size_t>(el) * kD * kD;
    for (int r = 0; r < kD; ++r)
      for (int u = 0; u < kD; ++u) {
        const std::size_t i = at + static_cast<std::size_t>(r * kD + u);
        job->t->rows[i] = g[r];
        job->t->cols[i] = g[u];
        job->t->values[i] = ke[static_cast<std::size_t>(r * kD + u)];
      }
  }
}

}  // namespace

Triplets ShellElements::tangent(const double* q) const {
  Triplets t;
  const std::size_t size = static_cast<std::size_t>(n_el()) * kD * kD;
  t.rows.resize(size);
  t.cols.resize(size);
  t.values.resize(size);
  const int threads = n_el() >= kMinParallelElements ? assembly_threads() : 1;
  TangentJob job{this, q, &t, threads};
  if (threads <= 1 || !run_chunks(threads, tangent_chunk, &job)) {
    job.n_chunks = 1;
    tangent_chunk(&job, 0);
  }
  return t;
}

Triplets ShellElements::mass() const {
  Triplets t;
  const double rt = in_.material.density * in_.material.thickness;
  std::int64_t g[kD];
  for (int el = 0; el < n_el(); ++el) {
    const ShellPoint* pt = points(el);
    dof_map(in_.connectivity.data() + 4 * el, g);
    for (int s = 0; s < kShellShapes; ++s)
      for (int u = 0; u < kShellShapes; ++u) {
        double m = 0.0;
        for (int q = 0; q < n_qp_; ++q) m += rt * pt[q].wda * pt[q].s[0][s] * pt[q].s[0][u];
        for (int d = 0; d < 3; ++d) {
          t.rows.push_back(g[3 * s + d]);
          t.cols.push_back(g[3 * u + d]);
          t.values.push_back(m);
        }
      }
  }
  return t;
}

void ShellElements::area_load(const double* p, double* f) const {
  std::fill(f, f + n(), 0.0);
  std::int64_t g[kD];
  for (int el = 0; el < n_el(); ++el) {
    const ShellPoint* pt = points(el);
    dof_map(in_.connectivity.data() + 4 * el, g);
    for (int s = 0; s < kShellShapes; ++s) {
      double a = 0.0;
      for (int q = 0; q < n_qp_; ++q) a += pt[q].wda * pt[q].s[0][s];
      for (int d = 0; d < 3; ++d) f[g[3 * s + d]] += a * p[d];
    }
  }
}

void ShellElements::pressure(const double* q, double p, double* f, Triplets* t) const {
  std::fill(f, f + n(), 0.0);
  double e[kD], ke[kD * kD];
  std::int64_t g[kD];
  for (int el = 0; el < n_el(); ++el) {
    const ShellPoint* pt = points(el);
    gather(el, q, e);
    dof_map(in_.connectivity.data() + 4 * el, g);
    std::fill(ke, ke + kD * kD, 0.0);
    for (int gp = 0; gp < n_qp_; ++gp) {
      const Kin k = kinematics(pt[gp], e);
      const double wp = pt[gp].w * p;
      for (int s = 0; s < kShellShapes; ++s)
        for (int d = 0; d < 3; ++d) f[g[3 * s + d]] += wp * pt[gp].s[0][s] * k.nt[d];
      if (t == nullptr) continue;
      for (int u = 0; u < kShellShapes; ++u)  // a3t_(u, c) = S_u,1 e_c x a_2 + S_u,2 a_1 x e_c
        for (int c = 0; c < 3; ++c) {
          double ec[3] = {0.0, 0.0, 0.0}, c1[3], c2[3];
          ec[c] = 1.0;
          cross(ec, k.a[1], c1);
          cross(k.a[0], ec, c2);
          for (int s = 0; s < kShellShapes; ++s)
            for (int d = 0; d < 3; ++d)
              ke[(3 * s + d) * kD + 3 * u + c] +=
                  wp * pt[gp].s[0][s] * (pt[gp].s[1][u] * c1[d] + pt[gp].s[2][u] * c2[d]);
        }
    }
    if (t == nullptr) continue;
    for (int r = 0; r < kD; ++r)
      for (int u = 0; u < kD; ++u) {
        t->rows.push_back(g[r]);
        t->cols.push_back(g[u]);
        t->values.push_back(ke[r * kD + u]);
      }
  }
}

// The shell family in the element registry (elements/registry.hpp): a Model whose elements are
// the shell body's (ShellData), its coordinates gathered through the connectivity.
namespace {

void shell_forces(const Model& m, int el, const double* e, double* fe, double* ke) {
  m.shell.elements->element_forces(el, e, fe, ke);
}

double shell_energy(const Model& m, int el, const double* e) {
  return m.shell.elements->element_energy(el, e);
}

/// No line sections: a shell's outputs are its sensors and surfaces (section_width 0).
void shell_section(const Model& /*m*/, const SamplePoints& /*p*/, int /*el*/, const double* /*e*/,
                   double* /*out*/) {}

}  // namespace

const ElementKernel shell_kernel{shell_forces, shell_energy, nullptr, shell_section, 0,
                                 false,        false,        false};

}  // namespace rancf
