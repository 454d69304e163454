// Contact between flexible bodies and self-contact (body_contact.hpp).
#include "contact/body_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "bodies/assembly.hpp"
#include "bodies/cable_shape.hpp"
#include "contact/body_broad.hpp"
#include "contact/contact_law.hpp"
#include "contact/contact_point.hpp"

namespace rancf {

namespace {

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

using Coords = std::array<double, kMaxElementDofs>;

/// The cable shape functions of element el of cb at xi and their first and second
/// xi-derivatives (cable_shape; N1, N2 may be null).
void shape(const ContactBody& cb, int el, double xi, double* N, double* N1, double* N2) {
  cable_shape(cb.weights.data() + 4 * el, cb.scales[sz(el)], xi, N, N1, N2);
}

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// A closest point on an element: its coordinate xi, the shape functions and their first and
/// second xi-derivatives there, and the curve's point and derivatives y, y', y''.
struct Projection {
  double xi = 0.0;
  double N[4], N1[4], N2[4];
  double y[3], y1[3], y2[3];
};

/// The closest point of element f (coordinates e) to x, xi in [0, 1] (project): Newton on
/// h = (y - x) . y' = 0 (step -h / h', or -h / |y'|^2 where h' <= 0) from the best of five
/// samples, or from start (>= 0: a closest point known nearby); it stops where the step is
/// below 1e-13 (or is clamped to nothing at an end) or the step that came to the point was
/// below 1e-8 (Newton's quadratic convergence: the point is then within about 1e-16),
/// keeping the point it evaluated.
void project(const Model& m, const ContactBody& cb, int f, const double* e, const double* x,
             Projection& p, double start = -1.0) {
  double best = start, dmin = 1e300;
  for (int s = 0; s <= 4 && start < 0.0; ++s) {
    const double xi = 0.25 * s;
    shape(cb, f, xi, p.N, nullptr, nullptr);
    contact_point::point_of(m, p.N, e, p.y);
    const double dd[3] = {p.y[0] - x[0], p.y[1] - x[1], p.y[2] - x[2]};
    if (dot3(dd, dd) < dmin) {
      dmin = dot3(dd, dd);
      best = xi;
    }
  }
  double xi = best, last = 1.0;  // last: the step that came to xi
  for (int it = 0; it < 30; ++it) {
    shape(cb, f, xi, p.N, p.N1, p.N2);
    contact_point::point_of(m, p.N, e, p.y);
    contact_point::point_of(m, p.N1, e, p.y1);
    contact_point::point_of(m, p.N2, e, p.y2);
    const double dd[3] = {p.y[0] - x[0], p.y[1] - x[1], p.y[2] - x[2]};
    const double h = dot3(dd, p.y1), dh = dot3(p.y1, p.y1) + dot3(dd, p.y2);
    const double step = dh > 0.0 ? -h / dh : -h / dot3(p.y1, p.y1);
    const double next = std::clamp(xi + step, 0.0, 1.0);
    if (std::abs(next - xi) < 1e-13 || last < 1e-8) break;
    last = std::abs(next - xi);
    xi = next;
  }
  p.xi = xi;
}

/// One body pair's geometry: bodies, radii, the element coordinates at a state.
struct Side {
  const Model* m = nullptr;
  const ContactBody* cb = nullptr;
  int body = 0, offset = 0;
};

/// Self-contact: whether point q of element e (at x) is out of reach of the part of element f
/// outside its excluded arc (body_contact.hpp): that part empty, or farther from x than reach
/// (hull_distance).  A point for which this holds has no kept projection within reach.
bool window_out_of_reach(const Side& B, int e, int q, int f, const double* eb, const double* x,
                         double reach) {
  double lo = 0.0, hi = 1.0;
  if (!outside_window(*B.cb, e, q, f, lo, hi)) return true;
  if (lo <= 0.0 && hi >= 1.0) return false;  // all of f counts: the capsule decided
  double P[4][3];
  control_points(*B.m, *B.cb, f, eb, P);
  return hull_distance(*B.cb, f, P, x, lo, hi) > reach;
}

/// A contact point x of side A against its closest point y(eta) on element f of side B
/// (body_contact.hpp): the gap and the normal (pair_geometry), and on demand (pair_gradient)
/// the gap's gradient G and (pair_hessian) Hessian Hg over the coordinates of both elements
/// (n = na + nb):
///   J dq = N_A de - N_B(eta) df  (the relative displacement at fixed eta),  G = J^T n,
///   Hg = (J^T P J - c b b^T) / rho,  P = I - n n^T,  c = |y'|^2 - rho n . y'',
///   b = (J^T y' + rho T^T n) / c (d eta = b . dq),  T dq = N_B'(eta) df,
/// from differentiating the projection (y - x) . y' = 0 (n . y' = 0 there); at a free end
/// eta is fixed (no b term).
struct Pair {
  bool kept = false;  ///< a valid projection (inside the element or at a free end)
  bool at_end = false;
  double xi = 0.0;  ///< the closest point's element coordinate
  double g = 0.0, rho = 0.0, n[3] = {0.0, 0.0, 0.0};
  const double* Na = nullptr;  ///< A's shape functions at the point
  Projection pr;               ///< B's closest point (shape functions, y, y', y'')
  // (the arrays are filled where they are asked for: pair_gradient, pair_hessian)
  std::array<double, 2 * kMaxElementDofs> G;
  double cc = 0.0;  ///< c of Hg (pair_hessian; 0: no b term)
  /// J and T by their columns, each with one entry at most: J(jd[a], a) = jc[a],
  /// T(jd[a], a) = tc[a] (jd[a] < 0: a zero column), and (if asked for) b (d eta = b . dq;
  /// zero at a free end or where the projection is no minimum): the friction's tangent
  std::array<double, 2 * kMaxElementDofs> jc, tc;
  std::array<int, 2 * kMaxElementDofs> jd;
  std::array<double, 2 * kMaxElementDofs> b;
};

void pair_geometry(const Side& A, const Side& B, int e, int q, int f, const double* ea,
                   const double* eb, Pair& out, double start = -1.0, bool ends = false) {
  const Model& ma = *A.m;
  const Model& mb = *B.m;
  out.Na = A.cb->N.data() + 4 * (e * A.cb->n_c + q);
  double x[3];
  contact_point::point_of(ma, out.Na, ea, x);
  project(mb, *B.cb, f, eb, x, out.pr, start);
  const double xi = out.pr.xi;
  out.xi = xi;
  out.at_end = xi == 0.0 || xi == 1.0;
  out.kept = false;
  const double* y = out.pr.y;
  const double d[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  out.rho = std::sqrt(dot3(d, d));
  out.g = out.rho - A.cb->radius - B.cb->radius;  // (also where not kept: each_near's bound)
  if (out.at_end && !ends && !((xi == 0.0 && f == 0) || (xi == 1.0 && f == mb.n_el - 1))) return;
  if (A.body == B.body) {  // self-contact: not near along the body
    const double s_y = B.cb->arc0[sz(f)] + xi * (B.cb->arc0[sz(f + 1)] - B.cb->arc0[sz(f)]);
    if (std::abs(point_arc(*A.cb, e, q) - s_y) < excluded_arc(*A.cb, *B.cb)) return;
  }
  out.kept = out.rho > 0.0;
  if (!out.kept) return;
  for (int i = 0; i < 3; ++i) out.n[i] = d[i] / out.rho;
}

/// J, T and G of a kept pair (pair_geometry).
void pair_gradient(const Model& ma, const Model& mb, Pair& out) {
  const int na = ma.nde(), n = na + mb.nde();
  std::fill(out.jc.begin(), out.jc.begin() + n, 0.0);
  std::fill(out.tc.begin(), out.tc.begin() + n, 0.0);
  std::fill(out.jd.begin(), out.jd.begin() + n, -1);
  for (int k = 0; k < 4; ++k) {
    const int oa = (k / 2) * ma.dpn + (k % 2) * ma.dim,
              ob = na + (k / 2) * mb.dpn + (k % 2) * mb.dim;
    for (int i = 0; i < ma.dim; ++i) {
      out.jd[sz(oa + i)] = out.jd[sz(ob + i)] = i;
      out.jc[sz(oa + i)] = out.Na[k];
      out.jc[sz(ob + i)] = -out.pr.N[k];
      out.tc[sz(ob + i)] = out.pr.N1[k];
    }
  }
  for (int a = 0; a < n; ++a) {
    const int i = out.jd[sz(a)];
    out.G[sz(a)] = i >= 0 ? out.jc[sz(a)] * out.n[i] : 0.0;
  }
}

/// c and b of Hg of a kept pair after pair_gradient (pair_geometry); Hg itself by entries
/// (hessian_entry).
void pair_hessian(int n, Pair& out) {
  const auto& jc = out.jc;
  const auto& jd = out.jd;
  const double* y1 = out.pr.y1;
  const double* y2 = out.pr.y2;
  std::fill(out.b.begin(), out.b.begin() + n, 0.0);
  out.cc = 0.0;
  if (out.at_end) return;
  const double cc = dot3(y1, y1) - out.rho * dot3(out.n, y2);
  if (!(cc > 0.0)) return;  // a projection that is no minimum: the first order terms only
  out.cc = cc;
  auto& bb = out.b;
  for (int a = 0; a < n; ++a) {
    const int i = jd[sz(a)];
    bb[sz(a)] = i >= 0 ? (jc[sz(a)] * y1[i] + out.rho * out.tc[sz(a)] * out.n[i]) / cc : 0.0;
  }
}

/// K = s Hg - w G dP^T (n x n, row-major) after pair_hessian, with
/// Hg = (J^T J - G G^T - c b b^T) / rho: K = G u^T + v b^T + (s / rho) J^T J,
/// u = -(s / rho) G - w dP, v = -(s c / rho) b, J^T J from J's columns (jc[a] jc[c] where both
/// move the same component).
void point_tangent(const Pair& p, int n, double s, double w, const double* dP, double* K) {
  const double sr = s / p.rho;
  std::array<double, 2 * kMaxElementDofs> u, v;
  for (int c = 0; c < n; ++c) {
    u[sz(c)] = -sr * p.G[sz(c)] - w * dP[c];
    v[sz(c)] = -sr * p.cc * p.b[sz(c)];
  }
  for (int a = 0; a < n; ++a) {
    const double ga = p.G[sz(a)], va = v[sz(a)];
    double* row = K + a * n;
    for (int c = 0; c < n; ++c) row[c] = ga * u[sz(c)] + va * p.b[sz(c)];
    const int i = p.jd[sz(a)];
    if (i < 0) continue;
    const double ja = sr * p.jc[sz(a)];
    for (int c = 0; c < n; ++c)
      if (p.jd[sz(c)] == i) row[c] += ja * p.jc[sz(c)];
  }
}

/// A point's weight and pressure and the pressure's slopes (point_force): w, pm, the
/// coefficients ck (d/dyf) and cv (d/dvf), and dP, the pressure's slope over the pair's
/// coordinates at the step's end (ck d/def + c1 d/de1; n values).
struct Slopes {
  double w, pm, ck, cv;
  const double* dP;
};

/// The regularized Coulomb friction of a point (body_contact.hpp) into fe, and (K not null)
/// minus its exact Jacobian into K (n x n, added): with the relative velocity u = J v (J at
/// the closest point eta), v_t = P u (P = I - n n^T), phi = v_t / s, s = sqrt(|v_t|^2 + eps^2),
///   f = J^T F,  F = -mu w p phi,
///   dF = -mu w (phi dp + p Pphi dv_t),  Pphi = (I - phi phi^T) / s,
///   dv_t = P J dv - P y.' (b . dq) - u_n dn - n (u . dn),  dn = (P J dq - P y' (b . dq)) / rho,
///   d(J^T) F = -T^T F (b . dq)
/// (y.' = N_B'(eta) v_B, u_n = n . u; b, T, y' of pair_geometry); p's slopes as the normal
/// force's (dP).
void friction(const BodyPair& bp, const Side& A, const Side& B, const Pair& pf, const Slopes& sl,
              const double* va, const double* vb, double* fe, double* K) {
  const Model& ma = *A.m;
  const Model& mb = *B.m;
  const int n = ma.nde() + mb.nde();
  const auto& jc = pf.jc;
  const auto& jd = pf.jd;
  double u[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < n; ++a)
    if (jd[sz(a)] >= 0) u[jd[sz(a)]] += jc[sz(a)] * (a < ma.nde() ? va[a] : vb[a - ma.nde()]);
  const double un = dot3(pf.n, u);
  double vt[3], phi[3];
  for (int i = 0; i < 3; ++i) vt[i] = u[i] - un * pf.n[i];
  const double s = std::sqrt(dot3(vt, vt) + bp.slip_velocity * bp.slip_velocity);
  for (int i = 0; i < 3; ++i) phi[i] = vt[i] / s;
  const double c = bp.friction * sl.w * sl.pm;
  std::array<double, 2 * kMaxElementDofs> Jphi{}, Tphi{};
  for (int a = 0; a < n; ++a) {
    const int i = jd[sz(a)];
    if (i < 0) continue;
    Jphi[sz(a)] = jc[sz(a)] * phi[i];
    Tphi[sz(a)] = pf.tc[sz(a)] * phi[i];
    fe[a] -= c * Jphi[sz(a)];
  }
  if (K == nullptr) return;
  double yd[3];  // y.' = N_B'(eta) v_B: the rate of the tangent at the material point
  contact_point::point_of(mb, pf.pr.N1, vb, yd);
  double Pyt[3], Pyd[3];
  const double nyt = dot3(pf.n, pf.pr.y1), nyd = dot3(pf.n, yd);
  for (int i = 0; i < 3; ++i) {
    Pyt[i] = pf.pr.y1[i] - nyt * pf.n[i];
    Pyd[i] = yd[i] - nyd * pf.n[i];
  }
  std::array<double, 3 * 2 * kMaxElementDofs> Dn{}, M{};  // dn/dq, then Pphi dv_t/d(q, v)
  std::array<double, 2 * kMaxElementDofs> uDn{};
  auto Jia = [&](int i, int a) { return jd[sz(a)] == i ? jc[sz(a)] : 0.0; };
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < n; ++a) {
      const double PJ = Jia(i, a) - pf.n[i] * pf.G[sz(a)];
      Dn[sz(i * n + a)] = (PJ - Pyt[i] * pf.b[sz(a)]) / pf.rho;
      uDn[sz(a)] += u[i] * Dn[sz(i * n + a)];
    }
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < n; ++a) {
      const double PJ = Jia(i, a) - pf.n[i] * pf.G[sz(a)];
      const double Vq = -Pyd[i] * pf.b[sz(a)] - un * Dn[sz(i * n + a)] - pf.n[i] * uDn[sz(a)];
      M[sz(i * n + a)] = sl.ck * Vq + sl.cv * PJ;
    }
  for (int a = 0; a < n; ++a) {  // Pphi M = (M - phi (phi^T M)) / s
    double pm = 0.0;
    for (int i = 0; i < 3; ++i) pm += phi[i] * M[sz(i * n + a)];
    for (int i = 0; i < 3; ++i) M[sz(i * n + a)] = (M[sz(i * n + a)] - phi[i] * pm) / s;
  }
  const double mw = bp.friction * sl.w;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      double v = mw * Jphi[sz(a)] * sl.dP[b];
      if (jd[sz(a)] >= 0) v += c * jc[sz(a)] * M[sz(jd[sz(a)] * n + b)];
      K[a * n + b] += v - sl.ck * c * Tphi[sz(a)] * pf.b[sz(b)];
    }
}

/// The force of point q of element e (side A, coordinates ea) against element f (side B,
/// coordinates eb): fe (n = na + nb: on e, then on f), with the step's mean pressure up to
/// (ea1, eb1) (null: statics); K (if not null, n x n): minus its Jacobian with respect to the
/// step's end, ck d/d(ea, eb) + cv d/d(va, vb) + c1 d/d(ea1, eb1) (friction: friction());
/// af > 0: the step's gap is the blend of the gaps at its ends (time-integration.md TI.16), the
/// start's coordinates (ea - (1 - af) ea1) / af projected from the alpha point's closest point
/// (kept at an end of the element, the distance to that end: the gap stays continuous where
/// the closest point passes to the next element within the step).  Returns
/// the gap (1e300: not kept); pw: the point's normal force.  xi (if not null): the
/// projection's start (< 0: none) and its closest point; clear: a gap at the alpha point above
/// which the step's gaps cannot reach zero (the points' motion in the step is below it);
/// seen (if not null): the gap at the alpha point's closest point on f, kept or not; ends (if
/// not null): the closest points at the step's end and start of the point's last force (< 0:
/// none), starts of their projections near the alpha point's, and set to those found.
double point_force(const BodyPair& bp, const Side& A, const Side& B, int e, int q, int f,
                   const double* ea, const double* eb, const double* ea1, const double* eb1,
                   const double* va, const double* vb, double* fe, double* pw, double ck = 1.0,
                   double cv = 0.0, double* K = nullptr, double c1 = 1.0, double af = 0.0,
                   double* xi = nullptr, double clear = 1e300, double* seen = nullptr,
                   double* ends = nullptr) {
  const int na = A.m->nde(), n = na + B.m->nde();
  Pair pf;
  pair_geometry(A, B, e, q, f, ea, eb, pf, xi != nullptr ? *xi : -1.0);
  if (xi != nullptr) *xi = pf.xi;
  if (seen != nullptr) *seen = pf.g;
  std::fill(fe, fe + n, 0.0);
  *pw = 0.0;
  if (!pf.kept) return 1e300;
  if (ea1 != nullptr && pf.g > clear) return pf.g;  // no pressure within the step
  const Penalty law{0.5 * bp.stiffness, bp.onset};
  double pm = 0.0, slope = 0.0, dpa = 0.0, dp1 = 0.0;  // the pressure and its slopes
  Pair p1, p0;
  if (ea1 == nullptr) {
    pm = law.p(pf.g);
    slope = law.slope(pf.g);
  } else {  // the step's mean pressure over [2 gs - g1, g1] (contact.hpp)
    // from the alpha point's closest point, or from the end's (start's) of the assembly before
    // where that is near it (the same closest point: Newton from nearer)
    auto from = [&](int k) {
      return ends != nullptr && ends[k] >= 0.0 && std::abs(ends[k] - pf.xi) < 0.1 ? ends[k] : pf.xi;
    };
    pair_geometry(A, B, e, q, f, ea1, eb1, p1, from(0));
    if (ends != nullptr) ends[0] = p1.xi;
    if (!p1.kept) p1 = pf;
    if (af > 0.0) {  // the step's start at the alpha point's closest point
      Coords ea0{}, eb0{};
      contact_point::step_start(ea, ea1, af, na, ea0.data());
      contact_point::step_start(eb, eb1, af, n - na, eb0.data());
      pair_geometry(A, B, e, q, f, ea0.data(), eb0.data(), p0, from(1), true);
      if (ends != nullptr) ends[1] = p0.xi;
    }
    const double gs = p0.kept ? (1.0 - af) * p1.g + af * p0.g : pf.g;
    mean_pressure(law, 2.0 * gs - p1.g, p1.g, pm, dpa, dp1);
  }
  if (pm == 0.0 && slope == 0.0 && dpa == 0.0 && dp1 == 0.0) return pf.g;
  pair_gradient(*A.m, *B.m, pf);
  // dP (the tangent's): the pressure's slope over the step's end; ga = 2 gs - g1 over the
  // alpha point and the end: 2 G and -G1 for gs = g(alpha), 2 G0 and (1 - 2 af) G1 -
  // 2 (1 - af) G0 for the blend
  std::array<double, 2 * kMaxElementDofs> dP{};
  if (K != nullptr) {
    pair_hessian(n, pf);
    if (ea1 != nullptr) pair_gradient(*A.m, *B.m, p1);
    if (p0.kept) pair_gradient(*A.m, *B.m, p0);
  }
  for (int a = 0; a < n && K != nullptr; ++a) {
    if (ea1 == nullptr)
      dP[sz(a)] = ck * slope * pf.G[sz(a)];
    else if (p0.kept)
      dP[sz(a)] = 2.0 * dpa * (ck - c1 * (1.0 - af)) * p0.G[sz(a)] +
                  c1 * (dp1 + (1.0 - 2.0 * af) * dpa) * p1.G[sz(a)];
    else
      dP[sz(a)] = 2.0 * ck * dpa * pf.G[sz(a)] + c1 * (dp1 - dpa) * p1.G[sz(a)];
  }
  const double w = A.cb->w[sz(e * A.cb->n_c + q)];
  *pw = w * pm;
  for (int a = 0; a < n; ++a) fe[a] = w * pm * pf.G[sz(a)];
  if (K != nullptr) point_tangent(pf, n, -w * ck * pm, w, dP.data(), K);
  if (bp.friction > 0.0 && va != nullptr && pm > 0.0) {
    const Slopes sl{w, pm, ck, cv, dP.data()};
    friction(bp, A, B, pf, sl, va, vb, fe, K);
  }
  return pf.g;
}

Side side(const System& s, const ContactSet& c, int body) {
  return Side{s.flex[sz(body)], &c.bodies[sz(body)], body, s.offset[sz(body)]};
}

/// Whether point x of side A (its element ea) can touch element fb of side B within a step: x
/// no farther from fb's capsule than A's tube radius, the onset and twice a step's motion of
/// A's element (the broad phase's margins, body_broad.hpp).
bool near(const Broad& br, int ea, int fb, const double* x, double ra, double onset) {
  const auto& cap = br.capsule[sz(fb)];
  return to_segment(cap.data(), x) <= cap[6] + ra + onset + br.moved[sz(ea)];
}

/// The distance within which a point of element ea can touch element fb within a step: the
/// tubes' radii, the onset and both elements' motion in a step (the broad phase's margins).
double reach(const Broad& br, int ea, int fb, const Side& A, const Side& B, const BodyPair& bp) {
  return A.cb->radius + B.cb->radius + bp.onset + br.moved[sz(ea)] + br.moved[sz(fb)];
}

/// Visit every kept (point, element) pair of every body pair in both directions at y:
/// fn(bp, A, B, e, q, f, ea, eb, fe, g, pw).  An element and itself are no pair (a point's
/// closest point on its own element is itself, within the arc excluded along the body);
/// with near_only (the forces) points out of reach of the element (near) are not projected.
template <class Fn>
void each_pair(const System& s, const ContactSet& c, const double* y, const double* y1,
               const double* v, bool near_only, Fn fn, const AssemblyTerms* tm = nullptr,
               double* K = nullptr) {
  if (c.body_pairs.empty()) return;
  const Broad br = spheres(s, c, y, y1);
  Coords ea{}, eb{}, ea1{}, eb1{}, va{}, vb{};
  std::array<double, 2 * kMaxElementDofs> fe{};
  for (const BodyPair& bp : c.body_pairs) {
    for (const auto& [ei, fi] : candidates(br, bp)) {
      if (bp.a == bp.b && ei == fi) continue;
      for (int dir = 0; dir < 2; ++dir) {
        if (bp.a == bp.b && dir == 1) continue;  // self: both orders come as candidates
        const Side A = side(s, c, dir == 0 ? bp.a : bp.b), B = side(s, c, dir == 0 ? bp.b : bp.a);
        const int e = dir == 0 ? ei : fi, f = dir == 0 ? fi : ei;
        element_coordinates(*A.m, y + A.offset, e, ea.data());
        element_coordinates(*B.m, y + B.offset, f, eb.data());
        if (y1 != nullptr) {
          element_coordinates(*A.m, y1 + A.offset, e, ea1.data());
          element_coordinates(*B.m, y1 + B.offset, f, eb1.data());
        }
        const double* pa1 = y1 != nullptr ? ea1.data() : nullptr;
        const double* pb1 = y1 != nullptr ? eb1.data() : nullptr;
        const bool rub = v != nullptr && bp.friction > 0.0;
        if (rub) {
          element_coordinates(*A.m, v + A.offset, e, va.data());
          element_coordinates(*B.m, v + B.offset, f, vb.data());
        }
        const double* pva = rub ? va.data() : nullptr;
        const double* pvb = rub ? vb.data() : nullptr;
        const int sa = br.start[sz(A.body)] + e, sb = br.start[sz(B.body)] + f;
        for (int q = 0; q < A.cb->n_c; ++q) {
          if (near_only) {
            double x[3];
            contact_point::point_of(*A.m, A.cb->N.data() + 4 * (e * A.cb->n_c + q), ea.data(), x);
            if (!near(br, sa, sb, x, A.cb->radius, bp.onset)) continue;
            if (A.body == B.body &&
                window_out_of_reach(B, e, q, f, eb.data(), x, reach(br, sa, sb, A, B, bp)))
              continue;
          }
          double pw = 0.0;
          const double g =
              point_force(bp, A, B, e, q, f, ea.data(), eb.data(), pa1, pb1, pva, pvb, fe.data(),
                          &pw, tm != nullptr ? tm->ck : 1.0, tm != nullptr ? tm->cv : 0.0, K,
                          tm != nullptr ? tm->c1 : 1.0, y1 != nullptr ? c.step_alpha_f : 0.0);
          fn(bp, A, B, e, q, f, ea.data(), eb.data(), pa1, pb1, pva, pvb, fe.data(), g, pw);
        }
      }
    }
  }
}

/// each_pair's visit over the near points of nl (update_near) at (y, y1, v), the forces: each
/// point's projection starts from its closest point of the assembly before; a point whose
/// kept lower bound of its gap less e's and f's drifts since (body_broad.hpp) exceeds both
/// elements' motion in the step, or farther from f's hull than the tubes' radii, the onset
/// and that motion, cannot touch f in the step and is not projected.
template <class Fn>
void each_near(const System& s, const ContactSet& c, NearList& nl, const double* y,
               const double* y1, const double* v, Fn fn, const AssemblyTerms& tm, double* K) {
  Coords ea{}, eb{}, ea1{}, eb1{}, va{}, vb{};
  std::array<double, 2 * kMaxElementDofs> fe{};
  const double af = y1 != nullptr ? c.step_alpha_f : 0.0;
  int key[4] = {-1, -1, -1, -1};  // pair, dir, e, f gathered
  double seg[6], off = 0.0;       // f's hull: its chord and the control points' distance
  for (NearPoint& p : nl.points) {
    const BodyPair& bp = c.body_pairs[sz(p.pair)];
    const Side A = side(s, c, p.dir == 0 ? bp.a : bp.b), B = side(s, c, p.dir == 0 ? bp.b : bp.a);
    const int ia = nl.start[sz(A.body)] + p.e, ib = nl.start[sz(B.body)] + p.f;
    const double drift = nl.drift_el[sz(ia)] + nl.drift_el[sz(ib)];
    const double clear = y1 != nullptr ? nl.moved_el[sz(ia)] + nl.moved_el[sz(ib)] : 0.0;
    if (p.gap - (drift - p.drift) > clear) continue;  // still clear of f
    const bool rub = v != nullptr && bp.friction > 0.0;
    if (key[0] != p.pair || key[1] != p.dir || key[2] != p.e || key[3] != p.f) {
      element_coordinates(*A.m, y + A.offset, p.e, ea.data());
      element_coordinates(*B.m, y + B.offset, p.f, eb.data());
      if (y1 != nullptr) {
        element_coordinates(*A.m, y1 + A.offset, p.e, ea1.data());
        element_coordinates(*B.m, y1 + B.offset, p.f, eb1.data());
      }
      if (rub) {
        element_coordinates(*A.m, v + A.offset, p.e, va.data());
        element_coordinates(*B.m, v + B.offset, p.f, vb.data());
      }
      double P[4][3];
      control_points(*B.m, *B.cb, p.f, eb.data(), P);
      for (int i = 0; i < 3; ++i) {
        seg[i] = P[0][i];
        seg[3 + i] = P[3][i];
      }
      off = std::max(to_segment(seg, P[1]), to_segment(seg, P[2]));
      key[0] = p.pair;
      key[1] = p.dir;
      key[2] = p.e;
      key[3] = p.f;
    }
    const double* pa1 = y1 != nullptr ? ea1.data() : nullptr;
    const double* pb1 = y1 != nullptr ? eb1.data() : nullptr;
    const double* pva = rub ? va.data() : nullptr;
    const double* pvb = rub ? vb.data() : nullptr;
    double x[3];
    contact_point::point_of(*A.m, A.cb->N.data() + 4 * (p.e * A.cb->n_c + p.q), ea.data(), x);
    p.drift = drift;
    p.gap = to_segment(seg, x) - off - A.cb->radius - B.cb->radius;  // f's hull: a lower bound
    if (p.gap > bp.onset + clear) continue;
    double pw = 0.0;
    const double g =
        point_force(bp, A, B, p.e, p.q, p.f, ea.data(), eb.data(), pa1, pb1, pva, pvb, fe.data(),
                    &pw, tm.ck, tm.cv, K, tm.c1, af, &p.xi, clear, &p.gap, p.xi_ends.data());
    fn(bp, A, B, p.e, p.q, p.f, ea.data(), eb.data(), pa1, pb1, pva, pvb, fe.data(), g, pw);
  }
}

/// T^T on the rows (and, for a matrix, the columns) of element blocks with a rotated clamp.
void rotate_pair(const Side& A, const Side& B, int e, int f, double* fe, double* K) {
  const int na = A.m->nde(), nb = B.m->nde(), n = na + nb;
  const bool ra = has_rotation(*A.m, e), rb = has_rotation(*B.m, f);
  if (!ra && !rb) return;
  auto vec = [&](double* v, int stride) {
    std::array<double, kMaxElementDofs> t{};
    if (ra) {
      for (int a = 0; a < na; ++a) t[sz(a)] = v[a * stride];
      rotate_back(*A.m, e, t.data(), nullptr);
      for (int a = 0; a < na; ++a) v[a * stride] = t[sz(a)];
    }
    if (rb) {
      for (int a = 0; a < nb; ++a) t[sz(a)] = v[(na + a) * stride];
      rotate_back(*B.m, f, t.data(), nullptr);
      for (int a = 0; a < nb; ++a) v[(na + a) * stride] = t[sz(a)];
    }
  };
  vec(fe, 1);
  if (K == nullptr) return;
  for (int j = 0; j < n; ++j) vec(K + j, n);      // columns: T^T K
  for (int i = 0; i < n; ++i) vec(K + i * n, 1);  // rows: (T^T K) T
}

/// Node blocks of the contacts' tangent: (row start, width, column start, width) and their
/// dense entries, summed over the element pairs that give them.
class NodeBlocks {
 public:
  /// No blocks, for a system of n coordinates: its blocks found through a table of n x n
  /// (small n; its entries of the blocks before set back) or a hash map.
  void reset(int n) {
    if (!table_.empty())
      for (const Head& h : heads_) table_[sz(h.r0) * sz(n_) + sz(h.c0)] = -1;
    if (n != n_) {
      n_ = n;
      table_.assign(n <= kTable ? sz(n) * sz(n) : 0, -1);
    }
    at_.clear();
    heads_.clear();
    vals_.clear();
  }
  /// Add the wr x wc block of K (row stride ld) at global rows r0.., columns c0...
  void add(int r0, int wr, int c0, int wc, const double* K, int ld) {
    std::size_t h = heads_.size();
    if (!table_.empty()) {
      int& t = table_[sz(r0) * sz(n_) + sz(c0)];
      if (t < 0) t = static_cast<int>(h);
      h = sz(t);
    } else {
      const std::int64_t k = static_cast<std::int64_t>(r0) * n_ + c0;
      h = at_.try_emplace(k, h).first->second;
    }
    if (h == heads_.size()) {
      heads_.push_back({r0, wr, c0, wc, vals_.size()});
      vals_.resize(vals_.size() + sz(wr * wc), 0.0);
    }
    double* v = vals_.data() + heads_[h].at;
    for (int i = 0; i < wr; ++i)
      for (int j = 0; j < wc; ++j) v[i * wc + j] += K[i * ld + j];
  }
  /// Each block to the sink once (as a square matrix over its rows and columns).
  void emit(const MatrixSink& add) const {
    std::array<int, 2 * kMaxElementDofs> idx{};
    std::array<double, 4 * kMaxElementDofs * kMaxElementDofs> M{};
    for (const Head& h : heads_) {
      const double* v = vals_.data() + h.at;
      const bool diag = h.r0 == h.c0;
      const int k = diag ? h.wr : h.wr + h.wc, co = diag ? 0 : h.wr;
      for (int i = 0; i < h.wr; ++i) idx[sz(i)] = h.r0 + i;
      for (int j = 0; j < h.wc; ++j) idx[sz(co + j)] = h.c0 + j;
      std::fill(M.begin(), M.begin() + k * k, 0.0);
      for (int i = 0; i < h.wr; ++i)
        for (int j = 0; j < h.wc; ++j) M[sz(i * k + co + j)] = v[i * h.wc + j];
      add(idx.data(), k, M.data());
    }
  }

 private:
  struct Head {
    int r0, wr, c0, wc;
    std::size_t at;
  };
  static constexpr int kTable = 1024;
  int n_ = -1;
  std::vector<int> table_;
  std::unordered_map<std::int64_t, std::size_t> at_;
  std::vector<Head> heads_;
  std::vector<double> vals_;
};

}  // namespace

void assemble_body_contact(const System& s, const ContactSet& c, const double* yf, const double* vf,
                           const double* y1, const AssemblyTerms& tm, double* r,
                           const MatrixSink* add) {
  // the points of element e against element f come one after the other: their forces and
  // tangents are summed, then given to r and the tangents to node blocks once per element
  // pair (flush); the node blocks (summed over the element pairs that share nodes, in both
  // orders) go to the sink at the end, each once
  std::vector<double> K(sz(4 * kMaxElementDofs * kMaxElementDofs)), Ksum;
  thread_local NodeBlocks blocks;
  blocks.reset(s.n);
  std::array<double, 2 * kMaxElementDofs> fsum{};
  Side sides[2];
  int key[4] = {-1, -1, -1, -1};  // bodies of A and B, e, f
  auto flush = [&]() {
    if (key[0] < 0) return;
    const Side &A = sides[0], &B = sides[1];
    const int e = key[2], f = key[3], na = A.m->nde(), n = na + B.m->nde();
    std::array<int, 2 * kMaxElementDofs> idx{};
    for (int a = 0; a < na; ++a) idx[sz(a)] = A.offset + e * A.m->dpn + a;
    for (int a = 0; a < n - na; ++a) idx[sz(na + a)] = B.offset + f * B.m->dpn + a;
    rotate_pair(A, B, e, f, fsum.data(), add != nullptr ? Ksum.data() : nullptr);
    for (int a = 0; a < n; ++a) r[idx[sz(a)]] -= fsum[sz(a)];
    if (add != nullptr) {
      const int nodes[4] = {idx[0], idx[sz(A.m->dpn)], idx[sz(na)], idx[sz(na + B.m->dpn)]};
      const int width[4] = {A.m->dpn, A.m->dpn, B.m->dpn, B.m->dpn};
      for (int bi = 0; bi < 4; ++bi)
        for (int bj = 0; bj < 4; ++bj)
          blocks.add(nodes[bi], width[bi], nodes[bj], width[bj],
                     Ksum.data() + (bi / 2) * na * n + (bi % 2) * width[bi] * n + (bj / 2) * na +
                         (bj % 2) * width[bj],
                     n);
    }
    key[0] = -1;
  };
  auto visit = [&](const BodyPair&, const Side& A, const Side& B, int e, int, int f, const double*,
                   const double*, const double*, const double*, const double*, const double*,
                   const double* fe, double, double pw0) {
    if (pw0 == 0.0) return;
    const int n = A.m->nde() + B.m->nde();
    if (key[0] != A.body || key[1] != B.body || key[2] != e || key[3] != f) {
      flush();
      sides[0] = A;
      sides[1] = B;
      key[0] = A.body;
      key[1] = B.body;
      key[2] = e;
      key[3] = f;
      std::fill(fsum.begin(), fsum.end(), 0.0);
      if (add != nullptr) Ksum.assign(sz(n * n), 0.0);
    }
    for (int a = 0; a < n; ++a) fsum[sz(a)] += fe[a];
    if (add != nullptr)  // the point's exact tangent (point_force)
      for (int a = 0; a < n * n; ++a) Ksum[sz(a)] += K[sz(a)];
  };
  double* Kp = add != nullptr ? K.data() : nullptr;
  NearList& nl = *c.near;
  std::unique_lock<std::mutex> lock(nl.mu, std::try_to_lock);
  if (lock.owns_lock() && !c.body_pairs.empty()) {  // the near points kept between assemblies
    update_near(s, c, yf, y1, nl);
    each_near(s, c, nl, yf, y1, vf, visit, tm, Kp);
  } else {  // another thread has them: from the broad phase
    each_pair(s, c, yf, y1, vf, true, visit, &tm, Kp);
  }
  flush();
  if (add != nullptr) blocks.emit(*add);
}

double body_contact_energy(const System& s, const ContactSet& c, const double* y) {
  double total = 0.0;
  each_pair(s, c, y, nullptr, nullptr, true,  // the points that can touch (g < 0)
            [&](const BodyPair& bp, const Side& A, const Side&, int e, int q, int, const double*,
                const double*, const double*, const double*, const double*, const double*,
                const double*, double g, double) {
              if (g < 0.0)
                total += A.cb->w[sz(e * A.cb->n_c + q)] *
                         Penalty{0.5 * bp.stiffness, bp.onset}.potential(g);
            });
  return total;
}

void body_contact_outputs(const System& s, const ContactSet& c, const double* y, double* out) {
  const std::size_t np = c.body_pairs.size();
  for (std::size_t k = 0; k < np; ++k) {
    out[kBodyOutputs * k] = 1e300;
    out[kBodyOutputs * k + 1] = out[kBodyOutputs * k + 2] = 0.0;
  }
  each_pair(s, c, y, nullptr, nullptr, false,
            [&](const BodyPair& bp, const Side&, const Side&, int, int, int, const double*,
                const double*, const double*, const double*, const double*, const double*,
                const double*, double g, double pw) {
              const auto k = static_cast<std::size_t>(&bp - c.body_pairs.data());
              double* o = out + kBodyOutputs * k;
              if (g < 1e299) o[0] = std::min(o[0], g);
              if (g < 0.0) {
                o[1] += 1.0;
                o[2] += pw;
              }
            });
}

}  // namespace rancf
