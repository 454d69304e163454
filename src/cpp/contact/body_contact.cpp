// Contact between flexible bodies and self-contact (body_contact.hpp).
#include "contact/body_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

/// The closest point of element f (coordinates e) to x: xi in [0, 1], the shape functions there.
double project(const Model& m, const ContactBody& cb, int f, const double* e, const double* x,
               double* N) {
  double best = 0.0, dmin = 1e300, y[3], N1[4], N2[4];
  for (int s = 0; s <= 4; ++s) {
    const double xi = 0.25 * s;
    shape(cb, f, xi, N, nullptr, nullptr);
    contact_point::point_of(m, N, e, y);
    const double dd[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    if (dot3(dd, dd) < dmin) {
      dmin = dot3(dd, dd);
      best = xi;
    }
  }
  double xi = best;
  for (int it = 0; it < 30; ++it) {
    double y1[3], y2[3];
    shape(cb, f, xi, N, N1, N2);
    contact_point::point_of(m, N, e, y);
    contact_point::point_of(m, N1, e, y1);
    contact_point::point_of(m, N2, e, y2);
    const double dd[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    const double h = dot3(dd, y1), dh = dot3(y1, y1) + dot3(dd, y2);
    const double step = dh > 0.0 ? -h / dh : -h / dot3(y1, y1);
    const double next = std::clamp(xi + step, 0.0, 1.0);
    const bool done = std::abs(next - xi) < 1e-15;
    xi = next;
    if (done) break;
  }
  shape(cb, f, xi, N, nullptr, nullptr);
  return xi;
}

/// One body pair's geometry: bodies, radii, the element coordinates at a state.
struct Side {
  const Model* m = nullptr;
  const ContactBody* cb = nullptr;
  int body = 0, offset = 0;
};

/// A contact point x of side A against its closest point y(eta) on element f of side B
/// (body_contact.hpp): the gap, the normal, and (Jacobian wanted) the gap's gradient G and
/// Hessian Hg over the coordinates of both elements (n = na + nb):
///   J dq = N_A de - N_B(eta) df  (the relative displacement at fixed eta),  G = J^T n,
///   Hg = (J^T P J - c b b^T) / rho,  P = I - n n^T,  c = |y'|^2 - rho n . y'',
///   b = (J^T y' + rho T^T n) / c (d eta = b . dq),  T dq = N_B'(eta) df,
/// from differentiating the projection (y - x) . y' = 0 (n . y' = 0 there); at a free end
/// eta is fixed (no b term).
struct Pair {
  bool kept = false;  ///< a valid projection (inside the element or at a free end)
  double g = 0.0, rho = 0.0, n[3] = {0.0, 0.0, 0.0};
  double Nb[4] = {0.0, 0.0, 0.0, 0.0};  ///< B's shape functions at the closest point
  std::array<double, 2 * kMaxElementDofs> G{};
  std::vector<double> Hg;  ///< (n x n), if asked for
};

void pair_geometry(const Side& A, const Side& B, int e, int q, int f, const double* ea,
                   const double* eb, bool hess, Pair& out) {
  const Model& ma = *A.m;
  const Model& mb = *B.m;
  const int na = ma.nde(), n = na + mb.nde();
  const double* Na = A.cb->N.data() + 4 * (e * A.cb->n_c + q);
  double x[3], y[3], Nb[4], Nb1[4], Nb2[4], y1[3], y2[3];
  contact_point::point_of(ma, Na, ea, x);
  const double xi = project(mb, *B.cb, f, eb, x, Nb);
  const bool at_end = xi == 0.0 || xi == 1.0;
  out.kept = false;
  if (at_end && !((xi == 0.0 && f == 0) || (xi == 1.0 && f == mb.n_el - 1))) return;
  if (A.body == B.body) {  // self-contact: not near along the body
    double s_pt = A.cb->arc0[sz(e)];
    for (int k = 0; k <= q; ++k) s_pt += A.cb->w[sz(e * A.cb->n_c + k)] * (k == q ? 0.5 : 1.0);
    const double s_y = B.cb->arc0[sz(f)] + xi * (B.cb->arc0[sz(f + 1)] - B.cb->arc0[sz(f)]);
    if (std::abs(s_pt - s_y) < M_PI * (A.cb->radius + B.cb->radius)) return;
  }
  shape(*B.cb, f, xi, Nb, Nb1, Nb2);
  for (int k = 0; k < 4; ++k) out.Nb[k] = Nb[k];
  contact_point::point_of(mb, Nb, eb, y);
  const double d[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  out.rho = std::sqrt(dot3(d, d));
  out.g = out.rho - A.cb->radius - B.cb->radius;
  out.kept = out.rho > 0.0;
  if (!out.kept) return;
  for (int i = 0; i < 3; ++i) out.n[i] = d[i] / out.rho;
  // J (3 x n) and T (3 x n), row-major
  std::array<double, 3 * 2 * kMaxElementDofs> J{}, T{};
  for (int k = 0; k < 4; ++k) {
    const int oa = (k / 2) * ma.dpn + (k % 2) * ma.dim,
              ob = na + (k / 2) * mb.dpn + (k % 2) * mb.dim;
    for (int i = 0; i < ma.dim; ++i) {
      J[sz(i * n + oa + i)] += Na[k];
      J[sz(i * n + ob + i)] -= Nb[k];
      T[sz(i * n + ob + i)] += Nb1[k];
    }
  }
  for (int a = 0; a < n; ++a) {
    double v = 0.0;
    for (int i = 0; i < 3; ++i) v += J[sz(i * n + a)] * out.n[i];
    out.G[sz(a)] = v;
  }
  if (!hess) return;
  contact_point::point_of(mb, Nb1, eb, y1);
  contact_point::point_of(mb, Nb2, eb, y2);
  out.Hg.assign(sz(n * n), 0.0);
  // J^T P J = J^T J - G G^T
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c) {
      double v = -out.G[sz(a)] * out.G[sz(c)];
      for (int i = 0; i < 3; ++i) v += J[sz(i * n + a)] * J[sz(i * n + c)];
      out.Hg[sz(a * n + c)] = v / out.rho;
    }
  if (at_end) return;
  const double cc = dot3(y1, y1) - out.rho * dot3(out.n, y2);
  if (!(cc > 0.0)) return;  // a projection that is no minimum: the first order terms only
  std::array<double, 2 * kMaxElementDofs> bb{};
  for (int a = 0; a < n; ++a) {
    double v = 0.0;
    for (int i = 0; i < 3; ++i)
      v += J[sz(i * n + a)] * y1[i] + out.rho * T[sz(i * n + a)] * out.n[i];
    bb[sz(a)] = v / cc;
  }
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c) out.Hg[sz(a * n + c)] -= cc * bb[sz(a)] * bb[sz(c)] / out.rho;
}

/// The force of point q of element e (side A, coordinates ea) against element f (side B,
/// coordinates eb): fe (n = na + nb: on e, then on f), with the step's mean pressure up to
/// (ea1, eb1) (null: statics); K (if not null, n x n): minus its Jacobian with respect to the
/// step's end, ck d/d(ea, eb) + c1 d/d(ea1, eb1).  Returns the gap (1e300: not kept); pw: the
/// point's normal force.
double point_force(const BodyPair& bp, const Side& A, const Side& B, int e, int q, int f,
                   const double* ea, const double* eb, const double* ea1, const double* eb1,
                   const double* va, const double* vb, double* fe, double* pw, double ck = 1.0,
                   double* K = nullptr, double c1 = 1.0) {
  const int n = A.m->nde() + B.m->nde();
  Pair pf;
  pair_geometry(A, B, e, q, f, ea, eb, K != nullptr, pf);
  std::fill(fe, fe + n, 0.0);
  *pw = 0.0;
  if (!pf.kept) return 1e300;
  const Penalty law{0.5 * bp.stiffness, bp.onset};
  double pm = 0.0, dpf = 0.0, dp1 = 0.0;  // the pressure and its slopes over gf and g1
  Pair p1;
  if (ea1 == nullptr) {
    pm = law.p(pf.g);
    dpf = law.slope(pf.g);
  } else {  // the step's mean pressure over [2 gf - g1, g1] (contact.hpp)
    pair_geometry(A, B, e, q, f, ea1, eb1, false, p1);
    if (!p1.kept) p1 = pf;
    const double ga = 2.0 * pf.g - p1.g;
    double dpa = 0.0;
    mean_pressure(law, ga, p1.g, pm, dpa, dp1);
    dpf = 2.0 * dpa;
    dp1 -= dpa;
  }
  if (pm == 0.0 && dpf == 0.0 && dp1 == 0.0) return pf.g;
  const double w = A.cb->w[sz(e * A.cb->n_c + q)];
  *pw = w * pm;
  for (int a = 0; a < n; ++a) fe[a] = w * pm * pf.G[sz(a)];
  if (bp.friction > 0.0 && va != nullptr && pm > 0.0) {
    // regularized Coulomb friction on the slip of x relative to B's material point y(eta):
    // f_t = -mu p v_t / sqrt(|v_t|^2 + eps^2), v_t = (I - n n^T)(v_x - v_y) (contact.hpp)
    const Model& ma = *A.m;
    const Model& mb = *B.m;
    const int na = ma.nde();
    const double* Na = A.cb->N.data() + 4 * (e * A.cb->n_c + q);
    double ux[3], uy[3], vt[3];
    contact_point::point_of(ma, Na, va, ux);
    contact_point::point_of(mb, pf.Nb, vb, uy);
    double un = 0.0;
    for (int i = 0; i < 3; ++i) un += pf.n[i] * (ux[i] - uy[i]);
    for (int i = 0; i < 3; ++i) vt[i] = ux[i] - uy[i] - un * pf.n[i];
    const double sl = std::sqrt(dot3(vt, vt) + bp.slip_velocity * bp.slip_velocity);
    for (int k = 0; k < 4; ++k) {
      const int oa = (k / 2) * ma.dpn + (k % 2) * ma.dim;
      const int ob = na + (k / 2) * mb.dpn + (k % 2) * mb.dim;
      for (int i = 0; i < ma.dim; ++i) {
        const double ft = -bp.friction * w * pm * vt[i] / sl;
        fe[oa + i] += Na[k] * ft;
        fe[ob + i] -= pf.Nb[k] * ft;
      }
    }
  }
  if (K == nullptr) return pf.g;
  const double* G1 = ea1 != nullptr ? p1.G.data() : pf.G.data();
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c)
      K[a * n + c] = -w * (ck * (dpf * pf.G[sz(a)] * pf.G[sz(c)] + pm * pf.Hg[sz(a * n + c)]) +
                           (ea1 != nullptr ? c1 * dp1 * pf.G[sz(a)] * G1[c] : 0.0));
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

/// Visit every kept (point, element) pair of every body pair in both directions at y:
/// fn(bp, A, B, e, q, f, ea, eb, fe, g, pw).  An element and itself are no pair (a point's
/// closest point on its own element is itself, within the arc excluded along the body);
/// with near_only (the forces) points out of reach of the element (near) are not projected.
template <class Fn>
void each_pair(const System& s, const ContactSet& c, const double* y, const double* y1,
               const double* v, bool near_only, Fn fn) {
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
          }
          double pw = 0.0;
          const double g = point_force(bp, A, B, e, q, f, ea.data(), eb.data(), pa1, pb1, pva, pvb,
                                       fe.data(), &pw);
          fn(bp, A, B, e, q, f, ea.data(), eb.data(), pa1, pb1, pva, pvb, fe.data(), g, pw);
        }
      }
    }
  }
}

/// Minus the Jacobian of a point's forces with friction (n x n into K) with respect to the
/// step's end: ck d/dyf + cv d/dvf + c1 d/dy1, by central differences of point_force (steps
/// 1e-7 (1 + |z|) and at most 1e-3 of the onset for positions, 1e-4 eps (1 + |z|) for
/// velocities, as contact.hpp's carried obstacles).
void friction_tangent(const BodyPair& bp, const Side& A, const Side& B, int e, int q, int f,
                      const double* ea, const double* eb, const double* ea1, const double* eb1,
                      const double* va, const double* vb, const AssemblyTerms& tm,
                      std::vector<double>& K) {
  const int na = A.m->nde(), n = na + B.m->nde();
  K.assign(sz(n * n), 0.0);
  const bool dyn = ea1 != nullptr;
  std::array<Coords, 6> z{};  // ea, eb, ea1, eb1, va, vb
  const double* src[6] = {ea, eb, ea1, eb1, va, vb};
  for (int k = 0; k < 6; ++k)
    if (src[k] != nullptr)
      std::copy(src[sz(k)], src[sz(k)] + (k % 2 == 0 ? na : n - na), z[sz(k)].begin());
  std::array<double, 2 * kMaxElementDofs> fp{}, fm{};
  const double coef[3] = {tm.ck, tm.c1, tm.cv};
  for (int set = 0; set < 3; ++set) {
    if ((set == 1 && !dyn) || coef[set] == 0.0) continue;
    for (int j = 0; j < n; ++j) {
      Coords& zz = z[sz(2 * set + (j < na ? 0 : 1))];
      double& x = zz[sz(j < na ? j : j - na)];
      const double x0 = x;
      const double h = set == 2 ? 1e-4 * bp.slip_velocity * (1.0 + std::abs(x0))
                                : std::min(1e-7 * (1.0 + std::abs(x0)), 1e-3 * bp.onset);
      double pw = 0.0;
      const double* z1a = dyn ? z[2].data() : nullptr;
      const double* z1b = dyn ? z[3].data() : nullptr;
      x = x0 + h;
      point_force(bp, A, B, e, q, f, z[0].data(), z[1].data(), z1a, z1b, z[4].data(), z[5].data(),
                  fp.data(), &pw);
      x = x0 - h;
      point_force(bp, A, B, e, q, f, z[0].data(), z[1].data(), z1a, z1b, z[4].data(), z[5].data(),
                  fm.data(), &pw);
      x = x0;
      for (int i = 0; i < n; ++i)
        K[sz(i * n + j)] -= coef[set] * (fp[sz(i)] - fm[sz(i)]) / (2.0 * h);
    }
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

}  // namespace

void assemble_body_contact(const System& s, const ContactSet& c, const double* yf, const double* vf,
                           const double* y1, const AssemblyTerms& tm, double* r,
                           const MatrixSink* add) {
  std::vector<double> K;
  each_pair(s, c, yf, y1, vf, true,
            [&](const BodyPair& bp, const Side& A, const Side& B, int e, int q, int f,
                const double* ea, const double* eb, const double* ea1, const double* eb1,
                const double* va, const double* vb, const double* fe, double, double pw0) {
              if (pw0 == 0.0) return;
              const int na = A.m->nde(), nb = B.m->nde(), n = na + nb;
              std::array<double, 2 * kMaxElementDofs> f0{};
              std::copy(fe, fe + n, f0.begin());
              std::array<int, 2 * kMaxElementDofs> idx{};
              for (int a = 0; a < na; ++a) idx[sz(a)] = A.offset + e * A.m->dpn + a;
              for (int a = 0; a < nb; ++a) idx[sz(na + a)] = B.offset + f * B.m->dpn + a;
              if (add != nullptr && va == nullptr) {  // frictionless: exact
                K.assign(sz(n * n), 0.0);
                double pw = 0.0;
                point_force(bp, A, B, e, q, f, ea, eb, ea1, eb1, nullptr, nullptr, f0.data(), &pw,
                            tm.ck, K.data(), tm.c1);
              } else if (add != nullptr) {  // friction: central differences of the point forces
                friction_tangent(bp, A, B, e, q, f, ea, eb, ea1, eb1, va, vb, tm, K);
              }
              rotate_pair(A, B, e, f, f0.data(), add != nullptr ? K.data() : nullptr);
              for (int a = 0; a < n; ++a) r[idx[sz(a)]] -= f0[sz(a)];
              if (add != nullptr) (*add)(idx.data(), n, K.data());
            });
}

double body_contact_energy(const System& s, const ContactSet& c, const double* y) {
  double total = 0.0;
  each_pair(s, c, y, nullptr, nullptr, false,
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
