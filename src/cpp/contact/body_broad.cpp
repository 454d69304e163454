// The broad phase of contact between flexible bodies (body_broad.hpp).
#include "contact/body_broad.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

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

}  // namespace rancf
