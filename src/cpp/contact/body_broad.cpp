// The broad phase of contact between flexible bodies (body_broad.hpp).
#include "contact/body_broad.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bodies/assembly.hpp"
#include "contact/contact_point.hpp"

namespace rancf {

namespace {

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

using Coords = std::array<double, kMaxElementDofs>;

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

double to_segment(const double* seg, const double* x) {
  const double ab[3] = {seg[3] - seg[0], seg[4] - seg[1], seg[5] - seg[2]};
  const double ax[3] = {x[0] - seg[0], x[1] - seg[1], x[2] - seg[2]};
  const double ll = dot3(ab, ab);
  const double t = ll > 0.0 ? std::clamp(dot3(ax, ab) / ll, 0.0, 1.0) : 0.0;
  const double d[3] = {ax[0] - t * ab[0], ax[1] - t * ab[1], ax[2] - t * ab[2]};
  return std::sqrt(dot3(d, d));
}

Broad spheres(const System& s, const ContactSet& c, const double* y, const double* y1) {
  Broad b;
  Coords e{}, e1{};
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    b.start.push_back(static_cast<int>(b.sphere.size()));
    const ContactBody& cb = c.bodies[k];
    if (cb.weights.empty()) continue;
    const Model& m = *s.flex[k];
    for (int el = 0; el < m.n_el; ++el) {
      element_coordinates(m, y + s.offset[k], el, e.data());
      std::vector<std::array<double, 3>> pts;
      for (int a = 0; a < 2; ++a) {
        std::array<double, 3> p{};
        for (int i = 0; i < m.dim; ++i) p[sz(i)] = e[sz(a * m.dpn + i)];
        pts.push_back(p);
      }
      for (int q = 0; q < cb.n_c; ++q) {
        std::array<double, 3> p{};
        contact_point::point_of(m, cb.N.data() + 4 * (el * cb.n_c + q), e.data(), p.data());
        pts.push_back(p);
      }
      std::array<double, 4> sp{};
      for (const auto& p : pts)
        for (int i = 0; i < 3; ++i) sp[sz(i)] += p[sz(i)] / static_cast<double>(pts.size());
      double rad = 0.0;
      for (const auto& p : pts) {
        const double dd[3] = {p[0] - sp[0], p[1] - sp[1], p[2] - sp[2]};
        rad = std::max(rad, std::sqrt(dot3(dd, dd)));
      }
      const double chord[3] = {pts[1][0] - pts[0][0], pts[1][1] - pts[0][1], pts[1][2] - pts[0][2]};
      double moved = 0.0;  // a step's motion: the spheres of its end too
      if (y1 != nullptr) {
        element_coordinates(m, y1 + s.offset[k], el, e1.data());
        for (int a = 0; a < 2; ++a) {
          double dd[3] = {0.0, 0.0, 0.0};
          for (int i = 0; i < m.dim; ++i) dd[i] = e1[sz(a * m.dpn + i)] - e[sz(a * m.dpn + i)];
          moved = std::max(moved, std::sqrt(dot3(dd, dd)));
        }
      }
      const double slack = 0.1 * std::sqrt(dot3(chord, chord)) + cb.radius + 2.0 * moved;
      sp[3] = rad + slack;
      b.sphere.push_back(sp);
      b.moved.push_back(2.0 * moved);
      std::array<double, 7> cap{};
      for (int i = 0; i < 3; ++i) {
        cap[sz(i)] = pts[0][sz(i)];
        cap[sz(3 + i)] = pts[1][sz(i)];
      }
      double off = 0.0;
      for (const auto& p : pts) off = std::max(off, to_segment(cap.data(), p.data()));
      cap[6] = off + slack;
      b.capsule.push_back(cap);
    }
  }
  b.start.push_back(static_cast<int>(b.sphere.size()));
  return b;
}

/// Candidate (element of a, element of b) pairs of one body pair whose spheres overlap (with the
/// onset), found through a uniform grid.
std::vector<std::pair<int, int>> candidates(const Broad& br, const BodyPair& bp) {
  std::vector<std::pair<int, int>> out;
  const int a0 = br.start[sz(bp.a)], a1 = br.start[sz(bp.a + 1)];
  const int b0 = br.start[sz(bp.b)], b1 = br.start[sz(bp.b + 1)];
  if (a0 == a1 || b0 == b1) return out;
  double h = 0.0;
  for (int i = a0; i < a1; ++i) h = std::max(h, 2.0 * br.sphere[sz(i)][3]);
  for (int i = b0; i < b1; ++i) h = std::max(h, 2.0 * br.sphere[sz(i)][3]);
  h += bp.onset;
  auto cell = [&](const std::array<double, 4>& sp, int k) {
    return static_cast<std::int64_t>(std::floor(sp[sz(k)] / h));
  };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  for (int i = b0; i < b1; ++i) {
    const auto& sp = br.sphere[sz(i)];
    grid[key(cell(sp, 0), cell(sp, 1), cell(sp, 2))].push_back(i - b0);
  }
  for (int i = a0; i < a1; ++i) {
    const auto& sp = br.sphere[sz(i)];
    const std::int64_t ci = cell(sp, 0), cj = cell(sp, 1), ck = cell(sp, 2);
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          auto it = grid.find(key(ci + di, cj + dj, ck + dk));
          if (it == grid.end()) continue;
          for (int f : it->second) {
            const auto& sq = br.sphere[sz(b0 + f)];
            if (cell(sq, 0) != ci + di || cell(sq, 1) != cj + dj || cell(sq, 2) != ck + dk)
              continue;  // a hash collision
            const double dd[3] = {sp[0] - sq[0], sp[1] - sq[1], sp[2] - sq[2]};
            if (std::sqrt(dot3(dd, dd)) <= sp[3] + sq[3] + bp.onset) out.emplace_back(i - a0, f);
          }
        }
  }
  return out;
}

double point_arc(const ContactBody& cb, int e, int q) {
  double s = cb.arc0[sz(e)];
  for (int k = 0; k <= q; ++k) s += cb.w[sz(e * cb.n_c + k)] * (k == q ? 0.5 : 1.0);
  return s;
}

double excluded_arc(const ContactBody& a, const ContactBody& b) {
  return M_PI * (a.radius + b.radius);
}

bool outside_window(const ContactBody& cb, int e, int q, int f, double& lo, double& hi) {
  const double s_pt = point_arc(cb, e, q), ex = excluded_arc(cb, cb);
  const double s0 = cb.arc0[sz(f)], len = cb.arc0[sz(f + 1)] - s0;
  lo = 0.0;
  hi = 1.0;
  if (!(len > 0.0)) return true;
  // one interval: s_pt is outside f
  if (s_pt <= s0)
    lo = std::max(lo, (s_pt + ex - s0) / len);
  else
    hi = std::min(hi, (s_pt - ex - s0) / len);
  return lo < hi;
}

void control_points(const Model& m, const ContactBody& cb, int el, const double* x,
                    double (*P)[3]) {
  const double* w = cb.weights.data() + 4 * el;
  const double l = cb.scales[sz(el)];
  const double c1 = l * w[0] / (3.0 * w[1]), c3 = -l * w[3] / (3.0 * w[2]);
  for (int k = 0; k < 4; ++k) P[k][2] = 0.0;
  for (int i = 0; i < m.dim; ++i) {
    const double r0 = x[i], d0 = x[m.dim + i], r1 = x[m.dpn + i], d1 = x[m.dpn + m.dim + i];
    P[0][i] = r0;
    P[1][i] = r0 + c1 * d0;
    P[2][i] = r1 + c3 * d1;
    P[3][i] = r1;
  }
}

double hull_distance(const ContactBody& cb, int el, const double (*P)[3], const double* x,
                     double lo, double hi) {
  const double* w = cb.weights.data() + 4 * el;
  if (!(w[0] > 0.0 && w[1] > 0.0 && w[2] > 0.0 && w[3] > 0.0)) return -1.0;
  double h[4][4];  // homogeneous control points (w P, w)
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 3; ++i) h[k][i] = w[k] * P[k][i];
    h[k][3] = w[k];
  }
  auto split = [&h](double t, bool left) {  // keep [0, t] (left) or [t, 1] of the curve
    double b[4][4][4];
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 4; ++i) b[0][k][i] = h[k][i];
    for (int r = 1; r < 4; ++r)
      for (int k = 0; k + r < 4; ++k)
        for (int i = 0; i < 4; ++i)
          b[r][k][i] = (1.0 - t) * b[r - 1][k][i] + t * b[r - 1][k + 1][i];
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 4; ++i) h[k][i] = left ? b[k][0][i] : b[3 - k][k][i];
  };
  if (hi < 1.0) split(hi, true);
  if (lo > 0.0) split(lo / hi, false);
  double Q[4][3];
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) Q[k][i] = h[k][i] / h[k][3];
  const double seg[6] = {Q[0][0], Q[0][1], Q[0][2], Q[3][0], Q[3][1], Q[3][2]};
  const double off = std::max(to_segment(seg, Q[1]), to_segment(seg, Q[2]));
  return to_segment(seg, x) - off;
}

namespace {

/// The control points of every element with contact curves at y (12 per element, Broad's
/// order) and the first of each body.
std::vector<double> all_control_points(const System& s, const ContactSet& c, const double* y,
                                       std::vector<int>* start) {
  std::vector<double> out;
  Coords e{};
  double P[4][3];
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    if (start != nullptr) start->push_back(static_cast<int>(out.size() / 12));
    const ContactBody& cb = c.bodies[k];
    if (cb.weights.empty()) continue;
    const Model& m = *s.flex[k];
    for (int el = 0; el < m.n_el; ++el) {
      element_coordinates(m, y + s.offset[k], el, e.data());
      control_points(m, cb, el, e.data(), P);
      for (const auto& p : P) out.insert(out.end(), p, p + 3);
    }
  }
  if (start != nullptr) start->push_back(static_cast<int>(out.size() / 12));
  return out;
}

/// The largest distance between corresponding control points of a and b.
double largest_motion(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i + 2 < a.size(); i += 3) {
    const double dd[3] = {a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]};
    d = std::max(d, dot3(dd, dd));
  }
  return std::sqrt(d);
}

/// Per element (12 coordinates of a and b each): the largest distance between its
/// corresponding control points times fac, into out (add: added to it).
void element_motion(const std::vector<double>& a, const std::vector<double>& b, double fac,
                    double* out, bool add = false) {
  for (std::size_t el = 0; 12 * el + 11 < a.size(); ++el) {
    double d = 0.0;
    for (std::size_t i = 12 * el; i < 12 * el + 12; i += 3) {
      const double dd[3] = {a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]};
      d = std::max(d, dot3(dd, dd));
    }
    out[el] = (add ? out[el] : 0.0) + fac * std::sqrt(d);
  }
}

std::int64_t near_key(const NearPoint& p) {
  return (((static_cast<std::int64_t>(p.pair) * 2 + p.dir) * (1 << 20) + p.e) * 128 + p.q) *
             (1 << 20) +
         p.f;
}

/// The near points of body pair k in order dir at the control points P (update_near).
void near_points(const System& s, const ContactSet& c, const double* y, int k, int dir,
                 const std::vector<std::pair<int, int>>& cand, const std::vector<double>& P,
                 const std::vector<int>& start, double margin, std::vector<NearPoint>& out) {
  const BodyPair& bp = c.body_pairs[sz(k)];
  const int ba = dir == 0 ? bp.a : bp.b, bb = dir == 0 ? bp.b : bp.a;
  const ContactBody &A = c.bodies[sz(ba)], &B = c.bodies[sz(bb)];
  const Model& ma = *s.flex[sz(ba)];
  const double reach = A.radius + B.radius + bp.onset + margin;
  Coords ea{};
  for (const auto& [ei, fi] : cand) {
    if (bp.a == bp.b && ei == fi) continue;
    const int e = dir == 0 ? ei : fi, f = dir == 0 ? fi : ei;
    element_coordinates(ma, y + s.offset[sz(ba)], e, ea.data());
    const auto* Pf = reinterpret_cast<const double (*)[3]>(P.data() + 12 * (start[sz(bb)] + f));
    const double seg[6] = {Pf[0][0], Pf[0][1], Pf[0][2], Pf[3][0], Pf[3][1], Pf[3][2]};
    const double off = std::max(to_segment(seg, Pf[1]), to_segment(seg, Pf[2]));
    for (int q = 0; q < A.n_c; ++q) {
      double x[3];
      contact_point::point_of(ma, A.N.data() + 4 * (e * A.n_c + q), ea.data(), x);
      double bound = to_segment(seg, x) - off;
      if (bound > reach) continue;
      if (ba == bb) {  // self-contact: f's part outside the excluded arc
        double lo = 0.0, hi = 1.0;
        if (!outside_window(B, e, q, f, lo, hi)) continue;
        if (lo > 0.0 || hi < 1.0) bound = std::max(bound, hull_distance(B, f, Pf, x, lo, hi));
        if (bound > reach) continue;
      }
      out.push_back(NearPoint{k, dir, e, q, f, -1.0});
    }
  }
}

}  // namespace

bool update_near(const System& s, const ContactSet& c, const double* y, const double* y1,
                 NearList& nl) {
  std::vector<int> start;
  const std::vector<double> P = all_control_points(s, c, y, &start);
  // the step's motion: to its end y1 and, where its gaps blend those of its ends (alpha_f
  // > 0), to its start y0 = (y - (1 - af) y1) / af, (1 - af) / af times as far
  const double af = y1 != nullptr ? c.step_alpha_f : 0.0;
  const std::size_t nel = P.size() / 12;
  nl.moved_el.assign(nel, 0.0);
  if (y1 != nullptr)
    element_motion(P, all_control_points(s, c, y1, nullptr),
                   af > 0.0 ? std::max(1.0, (1.0 - af) / af) : 1.0, nl.moved_el.data());
  const double moved = nel > 0 ? *std::max_element(nl.moved_el.begin(), nl.moved_el.end()) : 0.0;
  nl.moved = moved;
  if (nl.last.size() != P.size()) {
    nl.drift_el.assign(nel, 0.0);
    for (NearPoint& p : nl.points) p.gap = -1e300;
  } else {
    element_motion(P, nl.last, 1.0, nl.drift_el.data(), true);
  }
  nl.last = P;
  nl.start = start;
  if (nl.valid && nl.ref.size() == P.size() &&
      2.0 * (largest_motion(P, nl.ref) + moved) < nl.margin)
    return false;
  double rsum = 0.0;
  for (const BodyPair& bp : c.body_pairs)
    rsum = std::max(rsum, c.bodies[sz(bp.a)].radius + c.bodies[sz(bp.b)].radius);
  const double margin = std::max(rsum, 4.0 * moved);
  // spheres about the hulls, enlarged by the tube and half the margin: the candidate pairs
  Broad br;
  br.start = start;
  for (std::size_t k = 0; k + 1 < start.size(); ++k)
    for (int el = start[k]; el < start[k + 1]; ++el) {
      const double* p = P.data() + 12 * el;
      std::array<double, 4> sp{};
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 3; ++i) sp[sz(i)] += 0.25 * p[3 * j + i];
      double rad = 0.0;
      for (int j = 0; j < 4; ++j) {
        const double dd[3] = {p[3 * j] - sp[0], p[3 * j + 1] - sp[1], p[3 * j + 2] - sp[2]};
        rad = std::max(rad, std::sqrt(dot3(dd, dd)));
      }
      sp[3] = rad + c.bodies[k].radius + 0.5 * margin;
      br.sphere.push_back(sp);
    }
  std::unordered_map<std::int64_t, const NearPoint*> last;  // the closest points so far
  for (const NearPoint& p : nl.points) last[near_key(p)] = &p;
  std::vector<NearPoint> pts;
  for (std::size_t k = 0; k < c.body_pairs.size(); ++k) {
    const BodyPair& bp = c.body_pairs[k];
    const auto cand = candidates(br, bp);
    for (int dir = 0; dir < (bp.a == bp.b ? 1 : 2); ++dir)
      near_points(s, c, y, static_cast<int>(k), dir, cand, P, start, margin, pts);
  }
  for (NearPoint& p : pts) {
    const auto it = last.find(near_key(p));
    if (it == last.end()) continue;
    p.xi = it->second->xi;
    p.xi_ends = it->second->xi_ends;
    p.gap = it->second->gap;
    p.drift = it->second->drift;
  }
  nl.points = std::move(pts);
  nl.ref = P;
  nl.margin = margin;
  nl.valid = true;
  return true;
}

}  // namespace rancf
