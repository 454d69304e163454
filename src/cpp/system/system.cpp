#include "system/system.hpp"

#include <cmath>
#include <stdexcept>

#include "bodies/assembly.hpp"
#include "elements/rod.hpp"
#include "system/winch.hpp"

namespace rancf {

static_assert(kMaxLocal >= kMaxWindow, "a reduced node's window must fit a place map");

namespace {
std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

void System::setup() {
  offset.clear();
  block_size.clear();
  block_ku.clear();
  fixed.clear();
  n = 0;
  for (const Model* mod : flex) {
    offset.push_back(n);
    block_size.push_back(mod->n());
    block_ku.push_back(mod->ku());
    fixed.insert(fixed.end(), mod->supports.fixed, mod->supports.fixed + mod->n());
    n += mod->n();
  }
  for (const RigidInertia& b : rigid) {
    const int k = rigid_size(b);
    offset.push_back(n);
    block_size.push_back(k);
    block_ku.push_back(b.point_mass ? 0 : k - 1);
    fixed.insert(fixed.end(), sz(k), 0);
    n += k;
  }
  const int drums = winches != nullptr ? winches->drums : 0;
  for (int k = 0; k < drums; ++k) {  // driven drums: their length L (winch.hpp)
    offset.push_back(n);
    block_size.push_back(1);
    block_ku.push_back(0);
    fixed.push_back(0);
    ++n;
  }
  m = 0;
  joint_row.clear();
  slots.clear();
  for (const JointData& j : joints) {
    joint_row.push_back(m);
    m += joint_rows(j.info);
    if (j.info.kind == JointKind::sliding) slots.push_back(m - 1);
  }
  norm_row.assign(rigid.size(), -1);
  for (std::size_t r = 0; r < rigid.size(); ++r)
    if (rigid[r].dim == 3 && !rigid[r].point_mass) norm_row[r] = m++;
  linear_row = m;
  m += n_linear;
  maps.clear();
  for (const PlaceRef& p : places) maps.push_back(place_map(*this, p));
}

PlaceMap place_map(const System& s, const PlaceRef& p) {
  PlaceMap out;
  if (p.kind == PlaceKind::ground) return out;
  const bool node =
      p.kind == PlaceKind::cable || p.kind == PlaceKind::rod || p.kind == PlaceKind::beam;
  out.n = out.nq = place_size(p.kind, s.dim);
  if (node && s.flex[sz(p.body)]->reduced()) {  // the node's map over its window of y
    const Model& m = *s.flex[sz(p.body)];
    const Reduction& r = m.reduction;
    const int w = r.node_width,
              base = s.offset[sz(p.body)] + static_cast<int>(r.node_start[p.node]);
    const double* N = r.node_map + static_cast<std::ptrdiff_t>(p.node) * m.dpn * w;
    out.n = w;
    out.identity = false;
    out.reduced = true;
    for (int j = 0; j < w; ++j) out.index[j] = base + j;
    for (int i = 0; i < out.nq; ++i)
      for (int j = 0; j < w; ++j) out.T[i][j] = N[i * w + j];
    return out;
  }
  const int base =
      node ? s.offset[sz(p.body)] + p.node * s.flex[sz(p.body)]->dpn : s.rigid_offset(p.body);
  for (int i = 0; i < out.n; ++i) {
    out.index[i] = base + i;
    out.T[i][i] = 1.0;
  }
  if (!node || p.kind == PlaceKind::beam) return out;
  const Model& m = *s.flex[sz(p.body)];
  const int d = m.dim;
  for (int blk = 0; blk < 2; ++blk) {  // q = T y on a roller's position, a clamp's gradient
    const std::int64_t r = m.supports.rot_of_node[2 * p.node + blk];
    if (r < 0) continue;
    const double* bas = m.supports.rot + r * d * d;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) out.T[blk * d + i][blk * d + j] = bas[i * d + j];
    out.identity = false;
  }
  return out;
}

PlaceInfo place_info(const System& s, const PlaceRef& p, double t) {
  PlaceInfo info;
  info.kind = p.kind;
  info.dim = s.dim;
  for (int i = 0; i < 3; ++i) info.point[i] = p.point[i];
  info.angle0 = p.angle0;
  if (p.kind == PlaceKind::ground && p.motion >= 0)
    for (int i = 0; i < s.dim; ++i) info.point[i] += evaluate(s.tfs[sz(p.motion)], i, t).f;
  if (p.kind == PlaceKind::ground && p.rotation >= 0) {
    double rot[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < (s.dim == 2 ? 1 : 3); ++i) rot[i] = evaluate(s.tfs[sz(p.rotation)], i, t).f;
    rotation_matrix(s.dim, rot, info.frame);
  }
  if (p.kind == PlaceKind::rod) {
    const Model& m = *s.flex[sz(p.body)];
    info.tref = m.rod.tref + 3 * p.node;
    info.m1ref = m.rod.m1ref + 3 * p.node;
  }
  return info;
}

void place_at(const System& s, const PlaceRef& p, const PlaceMap& map, double t, const double* y,
              PlaceEval& out) {
  double u[kMaxLocal] = {};
  for (int i = 0; i < map.n; ++i) u[i] = y[map.index[i]];
  place_local(s, p, map, t, u, out);
}

void place_local(const System& s, const PlaceRef& p, const PlaceMap& map, double t, const double* u,
                 PlaceEval& out, bool frames) {
  PlaceInfo info = place_info(s, p, t);
  info.frames = frames;
  if (map.identity) {
    eval_place(info, u, out);
    return;
  }
  double q[kMaxLocal] = {};
  for (int i = 0; i < map.nq; ++i)
    for (int j = 0; j < map.n; ++j) q[i] += map.T[i][j] * u[j];
  eval_place(info, q, out);
  if (map.n == 0) return;
  // derivatives with respect to y's locals: d/dy = d/dq T
  double tmp[kMaxLocal];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < map.n; ++j) {
      tmp[j] = 0.0;
      for (int k = 0; k < map.nq; ++k) tmp[j] += out.dx[i][k] * map.T[k][j];
    }
    for (int j = 0; j < map.n; ++j) out.dx[i][j] = tmp[j];
    for (int f = 0; f < out.nf; ++f) {
      for (int j = 0; j < map.n; ++j) {
        tmp[j] = 0.0;
        for (int k = 0; k < map.nq; ++k) tmp[j] += out.df[f][i][k] * map.T[k][j];
      }
      for (int j = 0; j < map.n; ++j) out.df[f][i][j] = tmp[j];
    }
  }
  out.n = map.n;
}

}  // namespace rancf
