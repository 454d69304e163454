// Contact of flexible bodies with obstacles (contact.hpp).
#include "contact/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bodies/assembly.hpp"
#include "contact/body_contact.hpp"
#include "contact/contact_law.hpp"
#include "contact/contact_point.hpp"

namespace rancf {

namespace {

using namespace contact_point;  // NOLINT: the shared point helpers (contact_point.hpp)

/// One evaluation per point: everything outputs and energies need.
struct PointEval {
  double r[3];
  Gap gap;
  PointLaw law;
};

/// The slopes of the step's lower gap ga = 2 gs - g1 (step_gap) over the alpha point and the
/// end, rf and r1 taken apart: da[0..3) = d ga/d rf, da[3..6) = d ga/d r1 (normals nf, n0, n1
/// of the gaps at rf, r0, r1): 2 nf and -n1 for gs = g(rf); for the blend 2 n0 and
/// (1 - 2 af) n1 - 2 (1 - af) n0.
void ga_slopes(double af, const double* nf, const double* n0, const double* n1, double* da) {
  for (int i = 0; i < 3; ++i) {
    da[i] = af > 0.0 ? 2.0 * n0[i] : 2.0 * nf[i];
    da[3 + i] = af > 0.0 ? (1.0 - 2.0 * af) * n1[i] - 2.0 * (1.0 - af) * n0[i] : -n1[i];
  }
}

/// Visit the points of pair cp at state (y, v): fn(el, q, pose, PointEval&).  With y1 (a time
/// step's end; y, v its alpha point) the pressure is the step's mean, as assemble_contact's.
template <class Fn>
void each_point(const System& s, const ContactSet& c, const ContactPair& cp, const double* y,
                const double* v, const double* y1, Fn fn) {
  const ContactBody& cb = c.bodies[sz(cp.flex)];
  if (cb.n_c == 0) return;
  const Model& m = *s.flex[sz(cp.flex)];
  const int o = s.offset[sz(cp.flex)];
  const Obstacle& ob = c.obstacles[sz(cp.obstacle)];
  const Carrier cr = carrier(s, ob);
  double ub[kMaxBody] = {}, ubd[kMaxBody] = {}, ub1[kMaxBody] = {};
  gather_body(cr.map, y, ub);
  if (v != nullptr) gather_body(cr.map, v, ubd);
  if (y1 != nullptr) gather_body(cr.map, y1, ub1);
  PlaceEval pe;
  const Pose pose = pose_at(s, ob, cr, ub, &pe);
  const Pose pose1 = y1 != nullptr ? pose_at(s, ob, cr, ub1, nullptr) : pose;
  // the step's gap: the blend of its ends' (a fixed plane's is linear: the alpha point's)
  const double af =
      y1 == nullptr || (cr.fixed && ob.kind == ObstacleKind::plane) ? 0.0 : c.step_alpha_f;
  double ub0[kMaxBody] = {};
  if (af > 0.0) step_start(ub, ub1, af, cr.map.n, ub0);
  const Pose pose0 = af > 0.0 && !cr.fixed ? pose_at(s, ob, cr, ub0, nullptr) : pose;
  std::array<double, kMaxElementDofs> e{}, ev{}, e1{};
  for (int el = 0; el < m.n_el; ++el) {
    element_coordinates(m, y + o, el, e.data());
    if (v != nullptr) element_coordinates(m, v + o, el, ev.data());
    if (y1 != nullptr) element_coordinates(m, y1 + o, el, e1.data());
    for (int q = 0; q < cb.n_c; ++q) {
      const double* N = cb.N.data() + 4 * (el * cb.n_c + q);
      PointEval pt;
      point_of(m, N, e.data(), pt.r);
      gap(pose, pt.r, cb.radius, pt.gap, false);
      double gm[2] = {pt.gap.g, pt.gap.g};  // the step's gaps [2 gs - g(y1), g(y1)]
      if (y1 != nullptr) {
        double r1[3], r0[3];
        Gap g1, g0;
        point_of(m, N, e1.data(), r1);
        gap(pose1, r1, cb.radius, g1, false);
        const double gs = step_gap(pose0, cb.radius, pt.r, pt.gap.g, r1, g1.g, af, g0, r0);
        gm[0] = 2.0 * gs - g1.g;
        gm[1] = g1.g;
      }
      double u[3] = {0.0, 0.0, 0.0};
      if (v != nullptr) {
        point_of(m, N, ev.data(), u);
        if (!cr.fixed) {
          double rates[kMaxBody][3];
          point_rates(pe, pt.r, rates);
          for (int j = 0; j < cr.map.n; ++j)
            for (int i = 0; i < 3; ++i) u[i] -= rates[j][i] * ubd[j];
        }
      }
      point_law(cp, pt.gap, v != nullptr ? u : nullptr, y1 != nullptr ? gm : nullptr, false,
                pt.law);
      fn(el, q, pose, pt);
    }
  }
}

/// The velocity field of a carrying body: the material point at r moves with
/// sum_j rates_j(r) du_j, rates_j(r) = a_j + w_j x r (point_rates), and the fields' derivatives
/// over the body's coordinates (central differences of those exact first derivatives, step
/// 1e-6 (1 + |u_k|), as system_assembly.cpp does for rigid points).
struct Field {
  int n = 0;
  double a[kMaxBody][3], w[kMaxBody][3];
  double da[kMaxBody][kMaxBody][3], dw[kMaxBody][kMaxBody][3];  ///< [j][k]: d/du_k
};

void field_at(const System& s, const Obstacle& ob, const Carrier& cr, const double* ub,
              double (*a)[3], double (*w)[3]) {
  PlaceEval e;
  pose_at(s, ob, cr, ub, &e);
  for (int j = 0; j < cr.map.n; ++j) {  // w_j = 1/2 sum_k f_k x df_k/du_j, a_j = dx_j - w_j x x
    for (int i = 0; i < 3; ++i) w[j][i] = 0.0;
    for (int k = 0; k < e.nf; ++k) {
      const double df[3] = {e.df[k][0][j], e.df[k][1][j], e.df[k][2][j]};
      double c[3];
      cross(e.f[k], df, c);
      for (int i = 0; i < 3; ++i) w[j][i] += 0.5 * c[i];
    }
    double wx[3];
    cross(w[j], e.x, wx);
    for (int i = 0; i < 3; ++i) a[j][i] = e.dx[i][j] - wx[i];
  }
}

Field field_of(const System& s, const Obstacle& ob, const Carrier& cr, const double* ub) {
  Field f;
  f.n = cr.map.n;
  field_at(s, ob, cr, ub, f.a, f.w);
  double u[kMaxBody];
  for (int k = 0; k < f.n; ++k) u[k] = ub[k];
  for (int k = 0; k < f.n; ++k) {
    const double step = 1e-6 * (1.0 + std::abs(ub[k]));
    double ap[kMaxBody][3], wp[kMaxBody][3], am[kMaxBody][3], wm[kMaxBody][3];
    u[k] = ub[k] + step;
    field_at(s, ob, cr, u, ap, wp);
    u[k] = ub[k] - step;
    field_at(s, ob, cr, u, am, wm);
    u[k] = ub[k];
    for (int j = 0; j < f.n; ++j)
      for (int i = 0; i < 3; ++i) {
        f.da[j][k][i] = (ap[j][i] - am[j][i]) / (2.0 * step);
        f.dw[j][k][i] = (wp[j][i] - wm[j][i]) / (2.0 * step);
      }
  }
  return f;
}

/// rates_j(r) = a_j + w_j x r.
void rates_of(const Field& f, const double* r, double (*out)[3]) {
  for (int j = 0; j < f.n; ++j) {
    double c[3];
    cross(f.w[j], r, c);
    for (int i = 0; i < 3; ++i) out[j][i] = f.a[j][i] + c[i];
  }
}

/// A planar carried obstacle's point: the force F (d) and the body's (-F . rates_j), and their
/// Jacobian over z = (r, u_body) K = ck d/dzf + cv d/dzd + d/dz1 (nloc x nloc) from the exact
/// point law (point_law's A, B, Ga, G1) and the law's objectivity: F = R F_loc(rho, rho', gm)
/// with rho = R^T (r - c), rho' = R^T u in the body's frame, so that a turn dw of the body adds
/// dw x F and moves the point relative to it by -rates_j du_j (docs/guide/contact.md).
struct CarriedPoint {
  const double* r;            ///< the point at the alpha state
  const double* ur;           ///< its velocity (null: statics)
  const double* r1;           ///< at the step's end (null: no step)
  const double* ubd;          ///< the body's velocities
  double af = 0.0;            ///< > 0: the step's gap the blend of its ends' (step_gap)
  const Pose* p0 = nullptr;   ///< then the pose at the step's start
  const Field* f0 = nullptr;  ///< and the body's velocity field there
  /// the step's gaps where already known (null: found here): at the end, at the start (with
  /// the point there, r0) and the step's gap gs (step_gap)
  const Gap *g1 = nullptr, *g0 = nullptr;
  const double* r0 = nullptr;
  double gs = 0.0;
};

/// A gap's value and normal (its H is not needed where it is copied).
void copy_gap(const Gap& from, Gap& to) {
  to.g = from.g;
  std::copy(from.n, from.n + 3, to.n);
}

bool carried_tangent(const ContactPair& cp, const Pose& pf, const Pose& p1, const Field& ff,
                     const Field& f1, double rt, const CarriedPoint& pt, const AssemblyTerms& tm,
                     int d, double* F, double* K) {
  const int nb = ff.n, nloc = d + nb;
  const bool jac = K != nullptr;  // null: the forces alone (a residual)
  Gap gf, g1;
  gap(pf, pt.r, rt, gf, jac);
  double rates[kMaxBody][3], rates1[kMaxBody][3], om[3] = {0.0, 0.0, 0.0}, u[3] = {0.0, 0.0, 0.0};
  rates_of(ff, pt.r, rates);
  if (pt.ur != nullptr) {
    for (int i = 0; i < d; ++i) u[i] = pt.ur[i];
    for (int j = 0; j < nb; ++j)
      for (int i = 0; i < 3; ++i) {
        u[i] -= rates[j][i] * pt.ubd[j];
        om[i] += ff.w[j][i] * pt.ubd[j];
      }
  }
  double gm[2] = {gf.g, gf.g};
  // the slopes of ga = 2 gs - g1 (ga_slopes): over r at the alpha point and the end (da), over
  // the body's coordinates there (dau, over the end: dau + nb), gap slopes -n . rates_k
  double da[6], dau[2 * kMaxBody];
  ga_slopes(0.0, gf.n, gf.n, gf.n, da);
  for (int k = 0; k < nb; ++k) dau[k] = -2.0 * dot(gf.n, rates[k]);
  if (pt.r1 != nullptr) {
    if (pt.g1 != nullptr)
      copy_gap(*pt.g1, g1);
    else
      gap(p1, pt.r1, rt, g1, false);
    rates_of(f1, pt.r1, rates1);
    Gap g0;
    double r0[3], rates0[kMaxBody][3];
    const bool known = pt.g0 != nullptr && pt.r0 != nullptr;
    if (known) {
      copy_gap(*pt.g0, g0);
      std::copy(pt.r0, pt.r0 + 3, r0);
    }
    const double gs = known ? pt.gs : step_gap(*pt.p0, rt, pt.r, gf.g, pt.r1, g1.g, pt.af, g0, r0);
    gm[0] = 2.0 * gs - g1.g;
    gm[1] = g1.g;
    ga_slopes(pt.af, gf.n, g0.n, g1.n, da);
    if (pt.af > 0.0) rates_of(*pt.f0, r0, rates0);
    for (int k = 0; k < nb; ++k) {
      const double s1 = dot(g1.n, rates1[k]);
      if (pt.af > 0.0) {
        const double s0 = dot(g0.n, rates0[k]);
        dau[k] = -2.0 * s0;
        dau[nb + k] = 2.0 * (1.0 - pt.af) * s0 - (1.0 - 2.0 * pt.af) * s1;
      } else {
        dau[nb + k] = s1;
      }
    }
  }
  PointLaw pl;
  point_law(cp, gf, pt.ur != nullptr ? u : nullptr, pt.r1 != nullptr ? gm : nullptr, jac, pl);
  if (!pl.active) return false;
  for (int i = 0; i < d; ++i) F[i] = pl.F[i];
  for (int j = 0; j < nb; ++j) F[d + j] = -dot(pl.F, rates[j]);
  if (!jac) return true;
  std::fill(K, K + nloc * nloc, 0.0);
  // column b of group h: dF (3) and the extra part of the body's rows (beyond -dF . rates_j)
  auto put = [&](int b, double coef, const double* dF, const double* extra) {
    for (int i = 0; i < d; ++i) K[i * nloc + b] += coef * dF[i];
    for (int j = 0; j < nb; ++j)
      K[(d + j) * nloc + b] -= coef * (dot(dF, rates[j]) + (extra != nullptr ? extra[j] : 0.0));
  };
  auto mul = [](const double (*M)[3], const double* x, double* out) {
    for (int i = 0; i < 3; ++i) out[i] = M[i][0] * x[0] + M[i][1] * x[1] + M[i][2] * x[2];
  };
  const bool dyn = pt.r1 != nullptr;
  double extra[kMaxBody];
  for (int m = 0; m < d; ++m) {  // the point: r (alpha), its velocity, its end
    const double em[3] = {m == 0 ? 1.0 : 0.0, m == 1 ? 1.0 : 0.0, m == 2 ? 1.0 : 0.0};
    double oe[3], Boe[3], dF[3];
    cross(om, em, oe);  // du/dr = -[om]x
    mul(pl.B, oe, Boe);
    for (int i = 0; i < 3; ++i) dF[i] = pl.A[i][m] - Boe[i] + pl.Ga[i] * da[m];
    double Fw[3];
    for (int j = 0; j < nb; ++j) {  // d rates_j / dr = [w_j]x: F . (w_j x e_m)
      cross(pl.F, ff.w[j], Fw);
      extra[j] = Fw[m];
    }
    put(m, tm.ck, dF, extra);
    if (pt.ur != nullptr) {
      for (int i = 0; i < 3; ++i) dF[i] = pl.B[i][m];
      put(m, tm.cv, dF, nullptr);
    }
    if (dyn) {
      for (int i = 0; i < 3; ++i) dF[i] = pl.G1[i] * g1.n[m] + pl.Ga[i] * da[3 + m];
      put(m, tm.c1, dF, nullptr);
    }
  }
  for (int k = 0; k < nb; ++k) {  // the body: u (alpha), its velocity, its end
    double wF[3], wu[3], dV[3] = {0.0, 0.0, 0.0}, Ar[3], BV[3], dF[3];
    cross(ff.w[k], pl.F, wF);
    cross(ff.w[k], u, wu);
    for (int j = 0; j < nb && pt.ur != nullptr; ++j) {
      double c[3];
      cross(ff.dw[j][k], pt.r, c);
      for (int i = 0; i < 3; ++i) dV[i] += (ff.da[j][k][i] + c[i]) * pt.ubd[j];
    }
    for (int i = 0; i < 3; ++i) dV[i] += wu[i];
    mul(pl.A, rates[k], Ar);
    mul(pl.B, dV, BV);
    for (int i = 0; i < 3; ++i) dF[i] = wF[i] - Ar[i] - BV[i] + pl.Ga[i] * dau[k];
    for (int j = 0; j < nb; ++j) {  // d rates_j / du_k at r
      double c[3], dr[3];
      cross(ff.dw[j][k], pt.r, c);
      for (int i = 0; i < 3; ++i) dr[i] = ff.da[j][k][i] + c[i];
      extra[j] = dot(pl.F, dr);
    }
    put(d + k, tm.ck, dF, extra);
    if (pt.ur != nullptr) {
      mul(pl.B, rates[k], BV);
      for (int i = 0; i < 3; ++i) dF[i] = -BV[i];
      put(d + k, tm.cv, dF, nullptr);
    }
    if (dyn) {
      const double dg1 = dot(g1.n, rates1[k]);
      for (int i = 0; i < 3; ++i) dF[i] = -pl.G1[i] * dg1 + pl.Ga[i] * dau[nb + k];
      put(d + k, tm.c1, dF, nullptr);
    }
  }
  return true;
}

/// Whether no point of element el (coordinates ef; e1 at the step's end, null: statics) can
/// touch the obstacle (poses pf, p1): the gap is 1-Lipschitz in r (a plane's, a projection's
/// length), and a point r_q = sum_k N_qk b_k with N_q0 + N_q2 = 1 lies within
/// B = max|N_q2| |b_2 - b_0| + max|N_q1| |b_1| + max|N_q3| |b_3| of the node b_0, so that
/// g(r_q) is within B of g(b_0); the step's gaps [2 gf - g1, g1] are then all non-negative when
/// gf - Bf >= 0, g1 - B1 >= 0 and 2 (gf - Bf) - (g1 + B1) >= 0 (the points are skipped anyway).
bool out_of_reach(const Model& m, const ContactBody& cb, int el, const double* ef, const double* e1,
                  const Pose& pf, const Pose& p1) {
  double mx[4] = {0.0, 0.0, 0.0, 0.0};
  for (int q = 0; q < cb.n_c; ++q) {
    const double* N = cb.N.data() + 4 * (el * cb.n_c + q);
    if (std::abs(N[0] + N[2] - 1.0) > 1e-12) return false;  // no partition of unity
    for (int k = 1; k < 4; ++k) mx[k] = std::max(mx[k], std::abs(N[k]));
  }
  const int d = m.dim;
  auto lower = [&](const double* e, const Pose& pose, double& g0, double& bound) {
    const double* b[4];
    for (int k = 0; k < 4; ++k) b[k] = e + (k / 2) * m.dpn + (k % 2) * d;
    double chord = 0.0, t0 = 0.0, t1 = 0.0, r0[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i) {
      chord += (b[2][i] - b[0][i]) * (b[2][i] - b[0][i]);
      t0 += b[1][i] * b[1][i];
      t1 += b[3][i] * b[3][i];
      r0[i] = b[0][i];
    }
    bound = mx[2] * std::sqrt(chord) + mx[1] * std::sqrt(t0) + mx[3] * std::sqrt(t1);
    Gap g;
    gap(pose, r0, cb.radius, g, false);
    g0 = g.g;
  };
  double gf = 0.0, bf = 0.0;
  lower(ef, pf, gf, bf);
  if (gf - bf < 0.0) return false;
  if (e1 == nullptr) return true;
  double g1 = 0.0, b1 = 0.0;
  lower(e1, p1, g1, b1);
  return g1 - b1 >= 0.0 && 2.0 * (gf - bf) - (g1 + b1) >= 0.0;
}

/// A pair whose obstacle a rigid body carries: point forces and their differences over the point
/// and the body, mapped to the element's and the body's coordinates (couplings: the sink).
void carried_pair(const System& s, const ContactSet& c, const ContactPair& cp, const double* yf,
                  const double* vf, const double* y1, bool dyn, const AssemblyTerms& tm, double* r,
                  const MatrixSink* add) {
  {
    const ContactBody& cb = c.bodies[sz(cp.flex)];
    const Model& m = *s.flex[sz(cp.flex)];
    const int o = s.offset[sz(cp.flex)], d = m.dim, nde = m.nde();
    const Obstacle& ob = c.obstacles[sz(cp.obstacle)];
    const Carrier cr = carrier(s, ob);
    const int nb = cr.map.n, nall = nde + nb, nloc = d + nb;
    double ubf[kMaxBody] = {}, ubd[kMaxBody] = {}, ub1[kMaxBody] = {};
    gather_body(cr.map, yf, ubf);
    if (vf != nullptr) gather_body(cr.map, vf, ubd);
    if (dyn) gather_body(cr.map, y1, ub1);
    const Pose pf = pose_at(s, ob, cr, ubf, nullptr);
    const Pose p1 = dyn ? pose_at(s, ob, cr, ub1, nullptr) : pf;
    const double af = dyn ? c.step_alpha_f : 0.0;  // the step's gap: the blend of its ends'
    double ub0[kMaxBody] = {};
    if (af > 0.0) step_start(ubf, ub1, af, nb, ub0);
    const Pose p0 = af > 0.0 ? pose_at(s, ob, cr, ub0, nullptr) : pf;
    // planar bodies: the exact tangent (carried_tangent); in 3D central differences
    const bool planar = d == 2;
    Field ff, f1, f0;
    if (planar) {
      ff = field_of(s, ob, cr, ubf);
      f1 = dyn ? field_of(s, ob, cr, ub1) : ff;
      f0 = af > 0.0 ? field_of(s, ob, cr, ub0) : ff;
    }
    std::array<double, kMaxElementDofs> ef{}, ev{}, e1{}, e0{};
    std::array<double, kMaxAll> fe{};
    std::array<double, kMaxAll * kMaxAll> ke{};
    int idx[kMaxAll], shp[kMaxAll], cmp[kMaxAll];  // shape function and local component
    for (int a = 0; a < nde; ++a) {
      const int within = a % m.dpn;  // r, r' blocks; a rod's twist does not move r
      shp[a] = within < 2 * d ? 2 * (a / m.dpn) + within / d : kTwist;
      cmp[a] = within % d;
    }
    for (int j = 0; j < nb; ++j) {
      idx[nde + j] = cr.map.index[j];
      shp[nde + j] = kBody;
      cmp[nde + j] = d + j;
    }
    for (int el = 0; el < m.n_el; ++el) {
      element_coordinates(m, yf + o, el, ef.data());
      if (vf != nullptr) element_coordinates(m, vf + o, el, ev.data());
      if (dyn) element_coordinates(m, y1 + o, el, e1.data());
      if (af > 0.0) {  // no point within reach at the step's start and end: ga, g1 >= 0
        step_start(ef.data(), e1.data(), af, nde, e0.data());
        if (out_of_reach(m, cb, el, e0.data(), e1.data(), p0, p1)) continue;
      } else if (out_of_reach(m, cb, el, ef.data(), dyn ? e1.data() : nullptr, pf, p1)) {
        continue;
      }
      bool any = false;
      for (int q = 0; q < cb.n_c; ++q) {
        const double* N = cb.N.data() + 4 * (el * cb.n_c + q);
        double rf[3], r1[3] = {0.0, 0.0, 0.0};
        point_of(m, N, ef.data(), rf);
        Gap gf, g1, g0;
        gap(pf, rf, cb.radius, gf, false);
        double gmv[2] = {gf.g, gf.g};  // skip points out of contact over the whole step
        double r0[3] = {0.0, 0.0, 0.0}, gs = gf.g;
        if (dyn) {
          point_of(m, N, e1.data(), r1);
          gap(p1, r1, cb.radius, g1, false);
          gs = step_gap(p0, cb.radius, rf, gf.g, r1, g1.g, af, g0, r0);
          gmv[0] = 2.0 * gs - g1.g;
          gmv[1] = g1.g;
        }
        if (gmv[0] >= 0.0 && gmv[1] >= 0.0) continue;
        double u[3] = {0.0, 0.0, 0.0};
        if (vf != nullptr) point_of(m, N, ev.data(), u);
        const double wq = cb.w[sz(el * cb.n_c + q)];
        double F[kMaxLoc] = {}, K[kMaxLoc * kMaxLoc] = {};
        if (planar) {
          CarriedPoint pt{rf, vf != nullptr ? u : nullptr, dyn ? r1 : nullptr, ubd, af, &p0, &f0};
          if (dyn) {  // the gaps found above
            pt.g1 = &g1;
            pt.g0 = &g0;
            pt.r0 = r0;
            pt.gs = gs;
          }
          if (!carried_tangent(cp, pf, p1, ff, f1, cb.radius, pt, tm, d, F,
                               add != nullptr ? K : nullptr))
            continue;
        } else {
          double zf[kMaxLoc] = {}, zd[kMaxLoc] = {}, z1[kMaxLoc] = {};
          for (int i = 0; i < d; ++i) {
            zf[i] = rf[i];
            zd[i] = u[i];
            z1[i] = r1[i];
          }
          for (int j = 0; j < nb; ++j) {
            zf[d + j] = ubf[j];
            zd[d + j] = ubd[j];
            z1[d + j] = ub1[j];
          }
          const double* zdp = vf != nullptr ? zd : nullptr;
          const double* z1p = dyn ? z1 : nullptr;
          auto eval = [&](double* out) {
            carried_force(s, cp, ob, cr, cb.radius, zf, zdp, z1p, af, out, nullptr);
          };
          PointLaw pl;
          carried_force(s, cp, ob, cr, cb.radius, zf, zdp, z1p, af, F, &pl);
          if (!pl.active && !dyn) continue;
          if (add != nullptr) {  // ck d/dzf + cv d/dzd + d/dz1, central differences
            double* vars[3] = {zf, zd, z1};
            const double coef[3] = {tm.ck, vf != nullptr ? tm.cv : 0.0, dyn ? tm.c1 : 0.0};
            double fp[kMaxLoc], fm[kMaxLoc];
            for (int h = 0; h < 3; ++h) {
              if (coef[h] == 0.0) continue;
              for (int b = 0; b < nloc; ++b) {
                double& z = vars[h][b];
                // the friction turns over the slip velocity eps, the pressure over the onset
                // depth d: steps of 1e-4 eps and 1e-4 d keep the differences' error at 1e-8
                const double unit =
                    h == 1 ? 1e-4 * cp.slip_velocity : std::min(1e-6, 1e-4 * cp.onset);
                const double z00 = z, step = unit * (1.0 + std::abs(z00));
                z = z00 + step;
                eval(fp);
                z = z00 - step;
                eval(fm);
                z = z00;
                for (int a = 0; a < nloc; ++a)
                  K[a * nloc + b] += coef[h] * (fp[a] - fm[a]) / (2.0 * step);
              }
            }
          }
        }
        any = true;
        // map (r, ub) to (element, ub): dr = sum_k N_k de_k
        double sw[kMaxAll];  // the factor of each coordinate at the point
        for (int a = 0; a < nall; ++a)
          sw[a] = shp[a] >= 0 ? N[shp[a]] : (shp[a] == kBody ? 1.0 : 0.0);
        for (int a = 0; a < nall; ++a) {
          if (sw[a] == 0.0) continue;
          const double wa = wq * sw[a];
          fe[sz(a)] += wa * F[cmp[a]];
          if (add == nullptr) continue;
          const double* Ka = K + cmp[a] * nloc;
          double* row = ke.data() + sz(a * nall);
          for (int b = 0; b < nall; ++b) row[b] += wa * sw[b] * Ka[cmp[b]];
        }
      }
      if (!any) continue;
      if (has_rotation(m, el)) {  // back to y: T^T on the element's rows and columns
        std::array<double, kMaxElementDofs * kMaxElementDofs> kee{};
        for (int a = 0; a < nde; ++a)
          for (int b = 0; b < nde; ++b) kee[sz(a * nde + b)] = ke[sz(a * nall + b)];
        rotate_back(m, el, fe.data(), add != nullptr ? kee.data() : nullptr);
        for (int a = 0; a < nde; ++a)
          for (int b = 0; b < nde; ++b) ke[sz(a * nall + b)] = kee[sz(a * nde + b)];
        for (int j = 0; j < nb && add != nullptr; ++j) {
          std::array<double, kMaxElementDofs> col{}, rw{};
          for (int a = 0; a < nde; ++a) {
            col[sz(a)] = ke[sz(a * nall + nde + j)];
            rw[sz(a)] = ke[sz((nde + j) * nall + a)];
          }
          rotate_back(m, el, col.data(), nullptr);
          rotate_back(m, el, rw.data(), nullptr);
          for (int a = 0; a < nde; ++a) {
            ke[sz(a * nall + nde + j)] = col[sz(a)];
            ke[sz((nde + j) * nall + a)] = rw[sz(a)];
          }
        }
      }
      const int base = o + el * m.dpn;
      for (int a = 0; a < nde; ++a) idx[a] = base + a;
      for (int a = 0; a < nall; ++a) r[idx[a]] -= fe[sz(a)];
      std::fill(fe.begin(), fe.begin() + nall, 0.0);
      if (add == nullptr) continue;
      for (int a = 0; a < nall * nall; ++a) ke[sz(a)] = -ke[sz(a)];
      (*add)(idx, nall, ke.data());
      std::fill(ke.begin(), ke.begin() + nall * nall, 0.0);
    }
  }
}

/// A pair with a fixed obstacle: exact point tangents, accumulated per element over the shape
/// functions' products and added straight into the body's band block (or the sink).
template <int d>
void fixed_pair(const System& s, const ContactSet& c, const ContactPair& cp, int block,
                const double* yf, const double* vf, const double* y1, bool dyn,
                const AssemblyTerms& tm, double* r, BorderedLU* lu, const MatrixSink* add) {
  const ContactBody& cb = c.bodies[sz(cp.flex)];
  const Model& m = *s.flex[sz(cp.flex)];
  const int o = s.offset[sz(cp.flex)], nde = m.nde();
  const Obstacle& ob = c.obstacles[sz(cp.obstacle)];
  const Pose pose = pose_at(s, ob, Carrier{}, nullptr, nullptr);
  const bool rates = vf != nullptr && (cp.friction > 0.0 || cp.damping > 0.0);
  const bool jac = lu != nullptr || add != nullptr;
  int off[4];  // the element coordinate of shape function k's block
  for (int k = 0; k < 4; ++k) off[k] = (k / 2) * m.dpn + (k % 2) * d;
  std::array<double, kMaxElementDofs> ef{}, ev{}, e1{}, fe{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};  // (a rod's twist rows stay 0)
  double acc[10][d][d] = {};
  BandView band{nullptr, 0, 0, 0};
  if (lu != nullptr) band = lu->view(block);
  // the step's gap: the blend of its ends' (step_gap; a plane's is linear: the alpha point's)
  const double af = ob.kind == ObstacleKind::plane ? 0.0 : c.step_alpha_f;
  for (int el = 0; el < m.n_el; ++el) {
    element_coordinates(m, yf + o, el, ef.data());
    if (rates) element_coordinates(m, vf + o, el, ev.data());
    if (dyn) element_coordinates(m, y1 + o, el, e1.data());
    if (out_of_reach(m, cb, el, ef.data(), dyn ? e1.data() : nullptr, pose, pose)) continue;
    bool any = false;
    for (int q = 0; q < cb.n_c; ++q) {
      const double* N = cb.N.data() + 4 * (el * cb.n_c + q);
      double rf[3], r1[3];
      point_at<d>(off, N, ef.data(), rf);
      Gap gf, g1;
      gap(pose, rf, cb.radius, gf, jac);
      double gm[2] = {gf.g, gf.g}, da[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
      if (dyn) {
        double r0[3];
        Gap g0;
        point_at<d>(off, N, e1.data(), r1);
        gap(pose, r1, cb.radius, g1, false);
        const double gs = step_gap(pose, cb.radius, rf, gf.g, r1, g1.g, af, g0, r0);
        gm[0] = 2.0 * gs - g1.g;
        gm[1] = g1.g;
        if (jac) ga_slopes(af, gf.n, g0.n, g1.n, da);
      }
      if (gm[0] >= 0.0 && gm[1] >= 0.0) continue;
      double u[3] = {0.0, 0.0, 0.0};
      if (rates) point_at<d>(off, N, ev.data(), u);
      PointLaw pl;
      point_law(cp, gf, vf != nullptr ? u : nullptr, dyn ? gm : nullptr, jac, pl);
      if (!pl.active) continue;
      any = true;
      const double wq = cb.w[sz(el * cb.n_c + q)];
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < d; ++i) fe[sz(off[k] + i)] += wq * N[k] * pl.F[i];
      if (!jac) continue;
      // the step's gaps: d ga/dy1 = (ck d ga/drf + c1 d ga/dr1) . dr1 (step_gaps)
      double K[3][3];
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j)
          K[i][j] =
              tm.ck * pl.A[i][j] + tm.cv * pl.B[i][j] +
              (dyn ? pl.Ga[i] * (tm.ck * da[j] + tm.c1 * da[3 + j]) + tm.c1 * pl.G1[i] * g1.n[j]
                   : 0.0);
      // sum of w N_k N_l K over the points: the (k, l) and (l, k) blocks are equal
      for (int k = 0, kl = 0; k < 4; ++k)
        for (int l = k; l < 4; ++l, ++kl) {
          const double w2 = wq * N[k] * N[l];
          for (int i = 0; i < d; ++i)
            for (int j = 0; j < d; ++j) acc[kl][i][j] += w2 * K[i][j];
        }
    }
    if (!any) continue;
    if (jac)
      for (int k = 0, kl = 0; k < 4; ++k)
        for (int l = k; l < 4; ++l, ++kl)
          for (int i = 0; i < d; ++i)
            for (int j = 0; j < d; ++j) {
              ke[sz((off[k] + i) * nde + off[l] + j)] = acc[kl][i][j];
              ke[sz((off[l] + i) * nde + off[k] + j)] = acc[kl][i][j];
              acc[kl][i][j] = 0.0;
            }
    if (has_rotation(m, el)) rotate_back(m, el, fe.data(), jac ? ke.data() : nullptr);
    const int base = o + el * m.dpn;
    for (int a = 0; a < nde; ++a) r[base + a] -= fe[sz(a)];
    std::fill(fe.begin(), fe.begin() + nde, 0.0);
    if (!jac) continue;
    if (lu != nullptr) {  // the element's matrix lies in the band (as the element's own)
      const int eo = el * m.dpn;
      for (int j = 0; j < nde; ++j) {
        double* colj = &band.at(eo, eo + j);
        for (int i = 0; i < nde; ++i) colj[i * band.rs] -= ke[sz(i * nde + j)];
      }
    } else {
      int idx[kMaxElementDofs];
      for (int a = 0; a < nde; ++a) idx[a] = base + a;
      for (int a = 0; a < nde * nde; ++a) ke[sz(a)] = -ke[sz(a)];
      (*add)(idx, nde, ke.data());
    }
    std::fill(ke.begin(), ke.begin() + nde * nde, 0.0);
  }
}

}  // namespace

void assemble_contact(const System& s, const ContactSet& c, const double* yf, const double* vf,
                      const double* y1, const AssemblyTerms& tm, double* r, BorderedLU* lu,
                      const MatrixSink* add) {
  // a time step: the pressure is the mean over [2 g(yf) - g(y1), g(y1)] (contact.hpp)
  const bool dyn = vf != nullptr && y1 != yf;
  for (const ContactPair& cp : c.pairs) {
    if (c.bodies[sz(cp.flex)].n_c == 0) continue;
    if (c.obstacles[sz(cp.obstacle)].body >= 0)
      carried_pair(s, c, cp, yf, vf, y1, dyn, tm, r, add);
    else if (s.dim == 2)
      fixed_pair<2>(s, c, cp, cp.flex, yf, vf, y1, dyn, tm, r, lu, add);
    else
      fixed_pair<3>(s, c, cp, cp.flex, yf, vf, y1, dyn, tm, r, lu, add);
  }
  // between flexible bodies (body_contact.hpp)
  assemble_body_contact(s, c, yf, vf, dyn ? y1 : nullptr, tm, r, add);
}

double contact_energy(const System& s, const ContactSet& c, const double* y) {
  double total = 0.0;
  for (const ContactPair& cp : c.pairs) {
    const ContactBody& cb = c.bodies[sz(cp.flex)];
    each_point(s, c, cp, y, nullptr, nullptr, [&](int el, int q, const Pose&, const PointEval& pt) {
      total += cb.w[sz(el * cb.n_c + q)] * Penalty{cp.stiffness, cp.onset}.potential(pt.gap.g);
    });
  }
  return total + body_contact_energy(s, c, y);
}

void contact_outputs(const System& s, const ContactSet& c, const double* y, const double* v,
                     const double* y1, double* out) {
  std::fill(out, out + kContactOutputs * static_cast<std::ptrdiff_t>(c.obstacles.size()), 0.0);
  for (const ContactPair& cp : c.pairs) {
    const ContactBody& cb = c.bodies[sz(cp.flex)];
    const Model& m = *s.flex[sz(cp.flex)];
    const int o = s.offset[sz(cp.flex)];
    double* res = out + kContactOutputs * cp.obstacle;
    std::array<double, kMaxElementDofs> e{};
    int last = -1;
    each_point(s, c, cp, y, v, y1, [&](int el, int q, const Pose& pose, const PointEval& pt) {
      if (pt.law.active) {
        if (el != last) {
          element_coordinates(m, y + o, el, e.data());
          last = el;
        }
        double a[3];
        point_of(m, cb.N1.data() + 4 * (el * cb.n_c + q), e.data(), a);
        res[9] += cb.gw[sz(q)] * std::sqrt(dot(a, a));
        res[10] = std::max(res[10], -pt.gap.g);
      }
      if (!pt.law.active) return;
      const double wq = cb.w[sz(el * cb.n_c + q)];
      const double arm[3] = {pt.r[0] - pose.c[0], pt.r[1] - pose.c[1], pt.r[2] - pose.c[2]};
      double F[3], M[3];
      for (int i = 0; i < 3; ++i) {
        F[i] = wq * pt.law.F[i];
        res[i] += wq * pt.law.p * pt.gap.n[i];
        res[3 + i] += wq * pt.law.ft[i];
      }
      cross(arm, F, M);
      for (int i = 0; i < 3; ++i) res[6 + i] += M[i];
    });
  }
}

void contact_points(const System& s, const ContactSet& c, int k, const double* y, const double* v,
                    double* out) {
  const ContactPair& cp = c.pairs[sz(k)];
  const ContactBody& cb = c.bodies[sz(cp.flex)];
  each_point(s, c, cp, y, v, nullptr, [&](int el, int q, const Pose&, const PointEval& pt) {
    double* row = out + 8 * (el * cb.n_c + q);
    for (int i = 0; i < 3; ++i) {
      row[i] = pt.r[i];
      row[5 + i] = pt.law.ft[i];
    }
    row[3] = pt.gap.g;
    row[4] = pt.law.p;
  });
}

}  // namespace rancf
