// The points of contact with obstacles (contact.hpp): gaps to an obstacle, the contact law at a
// point, obstacles carried by rigid bodies (their pose and the rates of their material points),
// and the carried obstacles' point forces; shared by contact.cpp and body_contact.cpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "contact/contact.hpp"
#include "contact/contact_law.hpp"
#include "system/system.hpp"

namespace rancf::contact_point {

inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }

inline constexpr int kMaxBody = 7;            // coordinates of a carrying rigid body
inline constexpr int kMaxLoc = 3 + kMaxBody;  // a point's position and the body's
inline constexpr int kMaxAll =
    kMaxElementDofs + kMaxBody;                // an element's coordinates and the body's
inline constexpr int kTwist = -1, kBody = -2;  // coordinates that are no r block

/// An obstacle in world coordinates.
struct Pose {
  ObstacleKind kind = ObstacleKind::plane;
  double c[3] = {0.0, 0.0, 0.0};
  double a[3] = {0.0, 0.0, 1.0};
  double radius = 0.0;
};

/// (Made per contact point: gap() sets g and n always, H when asked for.)
struct Gap {
  double g = 0.0;
  double n[3] = {0.0, 0.0, 0.0};
  double H[3][3];
};

inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline void cross(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/// Gap, normal and (if hess) H = d2g/dr2 of a point r of a tube of radius rt (contact.hpp).
inline void gap(const Pose& o, const double* r, double rt, Gap& out, bool hess) {
  double d[3] = {r[0] - o.c[0], r[1] - o.c[1], r[2] - o.c[2]};
  if (o.kind == ObstacleKind::plane) {
    out.g = dot(o.a, d) - rt;
    for (int i = 0; i < 3; ++i) out.n[i] = o.a[i];
    if (hess)
      for (auto& row : out.H) row[0] = row[1] = row[2] = 0.0;
    return;
  }
  const bool cyl = o.kind == ObstacleKind::cylinder;
  const double da = cyl ? dot(o.a, d) : 0.0;
  for (int i = 0; i < 3; ++i) d[i] -= da * o.a[i];
  const double rho = std::sqrt(dot(d, d));
  out.g = rho - o.radius - rt;
  if (rho == 0.0) {  // on the axis or at the centre: no direction (no force)
    for (int i = 0; i < 3; ++i) out.n[i] = 0.0;
    if (hess)
      for (auto& row : out.H) row[0] = row[1] = row[2] = 0.0;
    return;
  }
  for (int i = 0; i < 3; ++i) out.n[i] = d[i] / rho;
  if (!hess) return;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double p = (i == j ? 1.0 : 0.0) - (cyl ? o.a[i] * o.a[j] : 0.0);
      out.H[i][j] = (p - out.n[i] * out.n[j]) / rho;
    }
}

/// The force per reference length on a point and its derivatives.
/// (Not zeroed as a whole on purpose, it is made per contact point: point_law sets active, p,
/// F and ft always, the derivatives when asked for and active.)
struct PointLaw {
  bool active = false;
  double p = 0.0;                 ///< pressure
  double F[3] = {0.0, 0.0, 0.0};  ///< p n + f_t
  double ft[3] = {0.0, 0.0, 0.0};
  double A[3][3];  ///< dF/dr (gap from r; the step's gaps held)
  double B[3][3];  ///< dF/du
  double Ga[3];    ///< dF/dga (the step's mean pressure)
  double G1[3];    ///< dF/dg1
};

/// The contact law at a point (contact.hpp): gap gf at r (H needed if derivs), relative velocity
/// u (null: statics), gm = {ga, g1} for the step's mean pressure (null: p from gf).
inline void point_law(const ContactPair& cp, const Gap& gf, const double* u, const double* gm,
                      bool derivs, PointLaw& out) {
  out.active = false;
  out.p = 0.0;
  for (int i = 0; i < 3; ++i) out.F[i] = out.ft[i] = 0.0;
  const Penalty law{cp.stiffness, cp.onset};
  double pe = 0.0, dpa = 0.0, dp1 = 0.0, dpr[3] = {0.0, 0.0, 0.0}, dpu[3] = {0.0, 0.0, 0.0};
  if (gm != nullptr) {
    mean_pressure(law, gm[0], gm[1], pe, dpa, dp1);
  } else {
    pe = law.p(gf.g);
    const double sl = law.slope(gf.g);
    for (int i = 0; i < 3; ++i) dpr[i] = sl * gf.n[i];
  }
  // Hunt-Crossley damping: p = pe (1 - chi g'), and the linear normal damping - s c_n g' while
  // in contact (pe > 0), s = min(pe / ps, 1) ramping in with the elastic pressure over the
  // onset (ps = k d / 2, its pressure at the onset's depth) so that the force is continuous
  // where a point comes into contact; clipped where a fast separation would pull
  const double dp1e = dp1, dpae = dpa, dpre[3] = {dpr[0], dpr[1], dpr[2]};  // d pe
  double p = pe;
  const double rate = u != nullptr ? dot(gf.n, u) : 0.0;
  if (u != nullptr && cp.damping > 0.0 && pe > 0.0) {
    const double f = 1.0 - cp.damping * rate;
    p = pe * std::max(f, 0.0);
    if (f > 0.0) {
      dp1 *= f;
      dpa *= f;
      for (int i = 0; i < 3 && derivs; ++i) {
        dpr[i] = dpr[i] * f - pe * cp.damping * dot(gf.H[i], u);  // d(n . u)/dr = H u
        dpu[i] = -pe * cp.damping * gf.n[i];
      }
    }
  }
  if (u != nullptr && cp.damping_normal > 0.0 && pe > 0.0) {
    const double ps = 0.5 * cp.stiffness * cp.onset;
    const double ramp = pe < ps ? pe / ps : 1.0, cn = ramp * cp.damping_normal;
    const double pd = p - cn * rate;
    if (pd > 0.0) {
      const double dramp = pe < ps ? -cp.damping_normal * rate / ps : 0.0;  // d(-cn g')/d pe
      dp1 += dramp * dp1e;
      dpa += dramp * dpae;
      for (int i = 0; i < 3 && derivs; ++i) {
        dpr[i] += dramp * dpre[i] - cn * dot(gf.H[i], u);
        dpu[i] -= cn * gf.n[i];
      }
    } else {  // a fast separation: no pressure, nothing pulls
      dp1 = dpa = 0.0;
      for (int i = 0; i < 3; ++i) dpr[i] = dpu[i] = 0.0;
    }
    p = std::max(pd, 0.0);
  }
  if (!(p > 0.0)) return;
  out.active = true;
  out.p = p;
  for (int i = 0; i < 3; ++i) out.F[i] = p * gf.n[i];
  double phi[3] = {0.0, 0.0, 0.0}, s = 1.0, un = 0.0, vt[3] = {0.0, 0.0, 0.0};
  const bool fr = u != nullptr && cp.friction > 0.0;
  if (fr) {
    un = dot(gf.n, u);
    for (int i = 0; i < 3; ++i) vt[i] = u[i] - gf.n[i] * un;
    s = std::sqrt(dot(vt, vt) + cp.slip_velocity * cp.slip_velocity);
    for (int i = 0; i < 3; ++i) {
      phi[i] = vt[i] / s;
      out.ft[i] = -cp.friction * p * phi[i];
      out.F[i] += out.ft[i];
    }
  }
  if (!derivs) return;
  const double mu = fr ? cp.friction : 0.0;
  double dir[3];  // F = p dir: dir = n - mu phi
  for (int i = 0; i < 3; ++i) {
    dir[i] = gf.n[i] - mu * phi[i];
    out.G1[i] = dir[i] * dp1;
    out.Ga[i] = dir[i] * dpa;
  }
  double Hu[3] = {0.0, 0.0, 0.0};
  if (u != nullptr)
    for (int i = 0; i < 3; ++i) Hu[i] = dot(gf.H[i], u);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      out.A[i][j] = dir[i] * dpr[j] + p * gf.H[i][j];
      out.B[i][j] = dir[i] * dpu[j];
    }
  if (!fr) return;
  // d phi = Pphi d vt, Pphi = (I - phi phi^T) / s; d vt/dr = -H un - n (H u)^T,
  // d vt/du = I - n n^T
  double Pphi[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Pphi[i][j] = ((i == j ? 1.0 : 0.0) - phi[i] * phi[j]) / s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double ar = 0.0, au = 0.0;
      for (int l = 0; l < 3; ++l) {
        const double dvr = -gf.H[l][j] * un - gf.n[l] * Hu[j];
        const double dvu = (l == j ? 1.0 : 0.0) - gf.n[l] * gf.n[j];
        ar += Pphi[i][l] * dvr;
        au += Pphi[i][l] * dvu;
      }
      out.A[i][j] -= mu * p * ar;
      out.B[i][j] -= mu * p * au;
    }
}

/// Where a pair's obstacle is and how its coordinates move it.
struct Carrier {
  bool fixed = true;
  PlaceRef place;
  PlaceMap map;
};

inline Carrier carrier(const System& s, const Obstacle& ob) {
  Carrier out;
  if (ob.body < 0) return out;
  out.fixed = false;
  out.place.kind = s.dim == 2 ? PlaceKind::rigid2d : PlaceKind::rigid3d;
  out.place.body = ob.body;
  for (int i = 0; i < 3; ++i) out.place.point[i] = ob.point[i];
  out.map = place_map(s, out.place);
  return out;
}

/// The body's place at local coordinates ub: the obstacle's pose and, if E is not null, the
/// place's evaluation (frames and derivatives).
inline Pose pose_at(const System& s, const Obstacle& ob, const Carrier& cr, const double* ub,
                    PlaceEval* E) {
  Pose o;
  o.kind = ob.kind;
  o.radius = ob.radius;
  if (cr.fixed) {
    for (int i = 0; i < 3; ++i) {
      o.c[i] = ob.point[i];
      o.a[i] = ob.dir[i];
    }
    return o;
  }
  PlaceEval local;
  PlaceEval& e = E != nullptr ? *E : local;
  place_local(s, cr.place, cr.map, 0.0, ub, e);
  for (int i = 0; i < 3; ++i) {
    o.c[i] = e.x[i];
    o.a[i] = ob.dir[0] * e.f[0][i] + ob.dir[1] * e.f[1][i] + ob.dir[2] * e.f[2][i];
  }
  return o;
}

/// d(material point at r)/d u_j = dx_j + w_j x (r - c), w_j = 1/2 sum_k f_k x df_k/du_j.
inline void point_rates(const PlaceEval& e, const double* r, double (*out)[3]) {
  const double d[3] = {r[0] - e.x[0], r[1] - e.x[1], r[2] - e.x[2]};
  for (int j = 0; j < e.n; ++j) {
    double w[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < e.nf; ++k) {
      const double df[3] = {e.df[k][0][j], e.df[k][1][j], e.df[k][2][j]};
      double c[3];
      cross(e.f[k], df, c);
      for (int i = 0; i < 3; ++i) w[i] += 0.5 * c[i];
    }
    double wd[3];
    cross(w, d, wd);
    for (int i = 0; i < 3; ++i) out[j][i] = e.dx[i][j] + wd[i];
  }
}

/// Gather a body's local coordinates.
inline void gather_body(const PlaceMap& map, const double* y, double* ub) {
  for (int i = 0; i < map.n; ++i) ub[i] = y[map.index[i]];
}

/// r = sum_k N_k e_k, blocks at off[k] of the element coordinates (z = 0 in 2D).
template <int D>
void point_at(const int* off, const double* N, const double* e, double* r) {
  r[0] = r[1] = r[2] = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < D; ++i) r[i] += N[k] * e[off[k] + i];
}

/// r = sum_k N_k e_k (blocks of the element coordinates; 3 components, zero z in 2D).
inline void point_of(const Model& m, const double* N, const double* e, double* r) {
  const int d = m.dim;
  const double *b0 = e, *b1 = e + d, *b2 = e + m.dpn, *b3 = e + m.dpn + d;  // blocks k = 0..3
  r[2] = 0.0;
  for (int i = 0; i < d; ++i) r[i] = N[0] * b0[i] + N[1] * b1[i] + N[2] * b2[i] + N[3] * b3[i];
}

/// The coordinates at a step's start from those at its alpha point and end (n values):
/// x0 = (xf - (1 - af) x1) / af, af > 0 (the rounding error eps |x| / af this makes in x0 is
/// multiplied back by af where x0 enters the step's gap).
inline void step_start(const double* xf, const double* x1, double af, int n, double* x0) {
  for (int i = 0; i < n; ++i) x0[i] = (xf[i] - (1.0 - af) * x1[i]) / af;
}

/// The step's gap of a point (time-integration.md TI.16): with af > 0 the blend of the gaps at
/// the step's ends, (1 - af) g1 + af g(r0) (obstacle at pose p0, g0 and r0 written), r0 the
/// point at the step's start (step_start); af = 0: the alpha point's gap gf.
inline double step_gap(const Pose& p0, double rt, const double* rf, double gf, const double* r1,
                       double g1, double af, Gap& g0, double* r0) {
  if (!(af > 0.0)) return gf;
  r0[2] = 0.0;
  step_start(rf, r1, af, 3, r0);
  gap(p0, r0, rt, g0, false);
  return (1.0 - af) * g1 + af * g0.g;
}

/// A carried obstacle's point: forces (dim on r, nb on the body) from z = (r, ub) at the alpha
/// point, their rates zd (null: statics), and at the step's end z1 (null: statics); af > 0:
/// the step's gap the blend of the gaps at its ends (step_gap), z0 from zf and z1.
inline void carried_force(const System& s, const ContactPair& cp, const Obstacle& ob,
                          const Carrier& cr, double rt, const double* zf, const double* zd,
                          const double* z1, double af, double* out, PointLaw* law) {
  const int d = s.dim, nb = cr.map.n;
  double r[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < d; ++i) r[i] = zf[i];
  PlaceEval e;
  const Pose o = pose_at(s, ob, cr, zf + d, &e);
  double rates[kMaxBody][3];
  point_rates(e, r, rates);
  Gap gf;
  gap(o, r, rt, gf, false);
  double u[3] = {0.0, 0.0, 0.0};
  if (zd != nullptr) {
    for (int i = 0; i < d; ++i) u[i] = zd[i];
    for (int j = 0; j < nb; ++j)
      for (int i = 0; i < 3; ++i) u[i] -= rates[j][i] * zd[d + j];
  }
  double gm[2] = {gf.g, gf.g};
  if (z1 != nullptr) {
    double r1[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i) r1[i] = z1[i];
    Gap g1, g0;
    gap(pose_at(s, ob, cr, z1 + d, nullptr), r1, rt, g1, false);
    double gs = gf.g;
    if (af > 0.0) {
      double z0[3 + kMaxBody], r0[3];
      step_start(zf, z1, af, d + nb, z0);
      gs = step_gap(pose_at(s, ob, cr, z0 + d, nullptr), rt, r, gf.g, r1, g1.g, af, g0, r0);
    }
    gm[0] = 2.0 * gs - g1.g;
    gm[1] = g1.g;
  }
  PointLaw pl;
  point_law(cp, gf, zd != nullptr ? u : nullptr, z1 != nullptr ? gm : nullptr, false, pl);
  for (int i = 0; i < d; ++i) out[i] = pl.F[i];
  for (int j = 0; j < nb; ++j) out[d + j] = -dot(pl.F, rates[j]);
  if (law != nullptr) *law = pl;
}

}  // namespace rancf::contact_point
