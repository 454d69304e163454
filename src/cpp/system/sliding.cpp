// Sliding joints (sliding.hpp; docs/derivations/sliding.md).
#include "system/sliding.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bodies/cable_shape.hpp"
#include "elements/registry.hpp"

namespace rancf {

namespace {
std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

void slide_point(const System& s, int body, const double* y, double sigma, SlidePoint& o) {
  o = SlidePoint{};
  const Model& m = *s.flex[sz(body)];
  const SlidingBody& g = s.sliding->of_body[sz(body)];
  const int ne = m.n_el, d = s.dim;
  double sg = sigma;
  if (g.closed) {
    sg = std::fmod(sigma, static_cast<double>(ne));
    if (sg < 0.0) sg += ne;
  }
  const int e = std::clamp(static_cast<int>(std::floor(sg)), 0, ne - 1);
  o.element = e;
  o.xi = sg - e;
  double n0[4], n1[4], n2[4];
  cable_shape(&g.weights[sz(4 * e)], g.scales[sz(e)], o.xi, n0, n1, n2);
  double d2[3][2 * kMaxLocal] = {};
  const PlaceKind kind = kernel_for(m).triads ? PlaceKind::rod : PlaceKind::cable;
  for (int k = 0; k < 2; ++k) {  // the element's nodes e, e + 1: positions and gradients
    PlaceRef p;
    p.kind = kind;
    p.body = body;
    p.node = e + k;
    const PlaceMap map = place_map(s, p);
    for (int j = 0; j < map.n; ++j) {
      const int c = o.n + j;
      o.index[c] = map.index[j];
      for (int i = 0; i < d; ++i) {
        const double pos = map.T[i][j], grad = map.T[d + i][j];
        o.dr[i][c] = n0[2 * k] * pos + n0[2 * k + 1] * grad;
        o.drs[i][c] = n1[2 * k] * pos + n1[2 * k + 1] * grad;
        d2[i][c] = n2[2 * k] * pos + n2[2 * k + 1] * grad;
      }
    }
    o.n += map.n;
  }
  for (int i = 0; i < d; ++i)
    for (int c = 0; c < o.n; ++c) {
      const double yc = y[o.index[c]];
      o.r[i] += o.dr[i][c] * yc;
      o.rs[i] += o.drs[i][c] * yc;
      o.rss[i] += d2[i][c] * yc;
    }
}

void sliding_rows(const System& s, const JointData& jd, const double* y, double t, double sigma,
                  double* g) {
  SlidePoint p;
  slide_point(s, jd.body, y, sigma, p);
  PlaceEval b;
  place_at(s, s.places[sz(jd.b)], s.maps[sz(jd.b)], t, y, b);
  for (int i = 0; i < s.dim; ++i) g[i] = p.r[i] - b.x[i];
}

void sliding_rates(const System& s, const double* y, const double* v, const double* lam, double t,
                   double* rates) {
  for (std::size_t k = 0; k < s.joints.size(); ++k) {
    const JointData& jd = s.joints[k];
    if (jd.info.kind != JointKind::sliding) continue;
    const int slot = s.joint_row[k] + s.dim;
    SlidePoint p;
    slide_point(s, jd.body, y, lam[slot], p);
    const PlaceMap& mb = s.maps[sz(jd.b)];
    PlaceEval b;
    place_at(s, s.places[sz(jd.b)], mb, t, y, b);
    double dot = 0.0, rr = 0.0;
    for (int i = 0; i < s.dim; ++i) {
      double rel = 0.0;  // the body's point's velocity less the place's, at a fixed sigma
      for (int j = 0; j < p.n; ++j) rel += p.dr[i][j] * v[p.index[j]];
      for (int j = 0; j < b.n; ++j) rel -= b.dx[i][j] * v[mb.index[j]];
      dot += p.rs[i] * rel;
      rr += p.rs[i] * p.rs[i];
    }
    rates[slot] = -dot / rr;
  }
}

void sliding_residual(const System& s, std::size_t k, const double* yf, const double* lam,
                      const double* y1, const AssemblyTerms& tm, double* r, const MatrixSink* add) {
  const JointData& jd = s.joints[k];
  const int d = s.dim, n = s.n, row0 = s.joint_row[k], slot = row0 + d;
  const double* l = lam + row0;
  const double sigma = lam[slot];
  sliding_rows(s, jd, y1, tm.t1, sigma, r + n + row0);
  SlidePoint p;
  slide_point(s, jd.body, yf, sigma, p);
  const PlaceRef& pb = s.places[sz(jd.b)];
  const PlaceMap& mb = s.maps[sz(jd.b)];
  PlaceEval b;
  place_at(s, pb, mb, tm.tf, yf, b);
  double h = 0.0;
  for (int i = 0; i < d; ++i) h += l[i] * p.rs[i];
  r[n + slot] = h;
  for (int j = 0; j < p.n; ++j)
    for (int i = 0; i < d; ++i) r[p.index[j]] += l[i] * p.dr[i][j];
  for (int j = 0; j < b.n; ++j)
    for (int i = 0; i < d; ++i) r[mb.index[j]] -= l[i] * b.dx[i][j];
  const bool turns = pb.kind == PlaceKind::rigid2d || pb.kind == PlaceKind::rigid3d;
  bool any = false;
  for (int i = 0; i < d; ++i) any = any || l[i] != 0.0;
  if (add == nullptr || !turns || !any) return;
  // -lambda . dx_B/du turns with a rigid body: central differences of the exact first
  // derivatives over its coordinates (step 1e-6 (1 + |u|))
  std::array<double, kMaxLocal> u{};
  for (int j = 0; j < mb.n; ++j) u[sz(j)] = yf[mb.index[j]];
  auto gen = [&](double* out) {
    PlaceEval e;
    place_local(s, pb, mb, tm.tf, u.data(), e);
    for (int j = 0; j < e.n; ++j) {
      out[j] = 0.0;
      for (int i = 0; i < d; ++i) out[j] -= l[i] * e.dx[i][j];
    }
  };
  const int w = mb.n;
  std::array<double, kMaxLocal * kMaxLocal> K{};
  std::array<double, kMaxLocal> fp{}, fm{};
  for (int c = 0; c < w; ++c) {
    const double u0 = u[sz(c)], step = 1e-6 * (1.0 + std::abs(u0));
    u[sz(c)] = u0 + step;
    gen(fp.data());
    u[sz(c)] = u0 - step;
    gen(fm.data());
    u[sz(c)] = u0;
    for (int a = 0; a < w; ++a) K[sz(a * w + c)] = tm.ck * (fp[sz(a)] - fm[sz(a)]) / (2.0 * step);
  }
  (*add)(mb.index, w, K.data());
}

void sliding_border(const System& s, std::size_t k, const double* yf, const double* lam,
                    const double* y1, const AssemblyTerms& tm, BorderedLU& lu) {
  const JointData& jd = s.joints[k];
  const int d = s.dim, row0 = s.joint_row[k], slot = row0 + d;
  const double* l = lam + row0;
  const double sigma = lam[slot];
  const PlaceRef& pb = s.places[sz(jd.b)];
  const PlaceMap& mb = s.maps[sz(jd.b)];
  SlidePoint p1, pf;
  slide_point(s, jd.body, y1, sigma, p1);
  slide_point(s, jd.body, yf, sigma, pf);
  PlaceEval b1, bf;
  place_at(s, pb, mb, tm.t1, y1, b1);
  place_at(s, pb, mb, tm.tf, yf, bf);
  double hss = 0.0;
  for (int q = 0; q < d; ++q) {
    const int row = row0 + q;
    for (int j = 0; j < p1.n; ++j) lu.add_q(row, p1.index[j], p1.dr[q][j]);  // dg/dy1
    for (int j = 0; j < b1.n; ++j) lu.add_q(row, mb.index[j], -b1.dx[q][j]);
    lu.add_d(row, slot, p1.rs[q]);                                           // dg/dsigma
    for (int j = 0; j < pf.n; ++j) lu.add_p(row, pf.index[j], pf.dr[q][j]);  // G(yf)^T
    for (int j = 0; j < bf.n; ++j) lu.add_p(row, mb.index[j], -bf.dx[q][j]);
    lu.add_d(slot, row, pf.rs[q]);  // dh/dlambda
    hss += l[q] * pf.rss[q];
  }
  for (int j = 0; j < pf.n; ++j) {  // d(G^T lambda)/dsigma and dh/dy1 = ck lambda . N'
    double v = 0.0;
    for (int q = 0; q < d; ++q) v += l[q] * pf.drs[q][j];
    lu.add_p(slot, pf.index[j], v);
    lu.add_q(slot, pf.index[j], tm.ck * v);
  }
  lu.add_d(slot, slot, hss);
}

}  // namespace rancf
