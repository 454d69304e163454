// Assembly of a system's balance, constraints and Jacobian (system.hpp).
//
// Exact derivatives: elements (their kernels), rigid bodies (rigid.hpp), joint Jacobians
// (joints.hpp).  By central differences of those exact first derivatives (step 1e-6 (1 + |u|)
// in each local coordinate, error of order its square): the second derivatives of the joint
// equations contracted with the multipliers, d(G^T lambda)/dy, and the tangents of springs and of
// loads at rigid-body points (whose direction of action turns with the body) -- small matrices
// over the local coordinates of one or two places; and (step eps^(1/3) (1 + |y|) along v) the
// derivative along v of a flexible body's tangent, for stiffness-proportional damping.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "bodies/assembly.hpp"
#include "bodies/inertia.hpp"
#include "contact/contact.hpp"
#include "fluid/fluid.hpp"
#include "system/sliding.hpp"
#include "system/spring_law.hpp"
#include "system/system.hpp"
#include "system/winch.hpp"

namespace rancf {

namespace {

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

/// Entries of the Jacobian that do not fit into a block's band, (row, column, value), nonzero;
/// kept from one assembly to the next for their memory (the solver swaps them in).
struct Far {
  std::vector<BorderedLU::Far> entries;
  void add(int i, int j, double v) { entries.push_back({i, j, v}); }
};

/// K (k x k, row-major) over global indices idx into lu's bands, or into far.
void add_matrix(BorderedLU& lu, const int* idx, int k, const double* K, Far& far) {
  thread_local std::vector<int> blk;  // each index's block
  blk.resize(sz(k));
  for (int a = 0; a < k; ++a) blk[sz(a)] = lu.block_of(idx[a]);
  for (int a = 0; a < k; ++a) {
    const int i = idx[a], bi = blk[sz(a)], ku = lu.block_ku(bi), o = lu.block_offset(bi);
    const BandView band = lu.view(bi);
    for (int b = 0; b < k; ++b) {
      const double v = K[a * k + b];
      if (v == 0.0) continue;
      const int j = idx[b];
      if (blk[sz(b)] == bi && std::abs(i - j) <= ku)
        band.at(i - o, j - o) += v;
      else
        far.add(i, j, v);
    }
  }
}

/// Local coordinates (y-space) of a place from y.
void gather(const PlaceMap& map, const double* y, double* u) {
  for (int i = 0; i < map.n; ++i) u[i] = y[map.index[i]];
}

/// Generalized forces of a force F (and torque T) at a place: dx^T F (+ the torque's).
void place_force(const PlaceEval& p, const double* F, const double* T, int dim, double* g,
                 bool rigid3d) {
  for (int j = 0; j < p.n; ++j) {
    g[j] = 0.0;
    for (int i = 0; i < dim; ++i) g[j] += p.dx[i][j] * F[i];
  }
  if (T == nullptr || p.nf < 3) return;
  if (dim == 2) {  // the frame turns with psi: d f_0 / d u_j = dpsi/du_j f_1
    for (int j = 0; j < p.n; ++j) {
      const double dpsi = p.df[0][0][j] * p.f[1][0] + p.df[0][1][j] * p.f[1][1];
      g[j] += T[2] * dpsi;
    }
    return;
  }
  // 3D: the rotation rate w_j with d f_k / d u_j = w_j x f_k: w_j = 1/2 sum_k f_k x df_k/du_j
  for (int j = 0; j < p.n; ++j) {
    double w[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      const double* f = p.f[k];
      const double d[3] = {p.df[k][0][j], p.df[k][1][j], p.df[k][2][j]};
      w[0] += 0.5 * (f[1] * d[2] - f[2] * d[1]);
      w[1] += 0.5 * (f[2] * d[0] - f[0] * d[2]);
      w[2] += 0.5 * (f[0] * d[1] - f[1] * d[0]);
    }
    g[j] += T[0] * w[0] + T[1] * w[1] + T[2] * w[2];
  }
  (void)rigid3d;
}

/// Whether a place's local coordinate j enters its position or frame nonlinearly (a rotation:
/// a cable's or rod's gradient and twist, a beam's or rigid body's angle, a quaternion); the
/// derivatives of the other (positions) are constant.
bool nonlinear_local(PlaceKind kind, int dim, int j) {
  switch (kind) {
    case PlaceKind::cable:
    case PlaceKind::rod:
      return j >= dim;
    case PlaceKind::beam:
    case PlaceKind::rigid2d:
      return j == 2;
    case PlaceKind::rigid3d:
      return j >= 3;
    default:
      return false;
  }
}

/// Central differences of F(u) (k values) with respect to u (k values): K[a][b] = dF_a/du_b,
/// only for the columns b with vary[b] (the others are zero).
template <class Fn>
void jacobian_fd(int k, double* u, Fn fn, double* K, const bool* vary = nullptr) {
  double fp[2 * kMaxLocal], fm[2 * kMaxLocal];
  for (int b = 0; b < k; ++b) {
    if (vary != nullptr && !vary[b]) {
      for (int a = 0; a < k; ++a) K[a * k + b] = 0.0;
      continue;
    }
    const double u0 = u[b], h = 1e-6 * (1.0 + std::abs(u0));
    u[b] = u0 + h;
    fn(fp);
    u[b] = u0 - h;
    fn(fm);
    u[b] = u0;
    for (int a = 0; a < k; ++a) K[a * k + b] = (fp[a] - fm[a]) / (2.0 * h);
  }
}

}  // namespace

namespace {

void stiffness_damping(const Model& mod, double beta, const double* y, const double* v,
                       const AssemblyTerms& tm, double* r, const BandView* jac) {
  // The force beta K_T(y) v of Rayleigh's stiffness-proportional damping, K_T the tangent
  // stiffness of the elements at y.  Its derivatives: d/dv = beta K_T, and d/dy, whose column
  // k is beta sum_j d2 f / dy_j dy_k v_j = beta (d/de K_T(y + e v))_{., k} (the second
  // derivatives of f are symmetric): the tangent's derivative along v, by central differences
  // of the tangent with the step h |v|_inf = eps^(1/3) (1 + |y|_inf).
  const int nb = mod.n(), ku = mod.ku();
  const auto size = static_cast<std::size_t>((2 * ku + 1) * nb);
  thread_local std::vector<double> kb, kp, f, kv, ys;
  kb.assign(size, 0.0);
  f.assign(sz(nb), 0.0);
  kv.assign(sz(nb), 0.0);
  const BandView k0 = numpy_band(kb.data(), nb, ku);
  assemble(mod, y, f.data(), &k0, 1.0);
  band_matvec(kb.data(), v, nb, ku, kv.data());
  for (int i = 0; i < nb; ++i) r[i] += beta * kv[sz(i)];
  if (jac == nullptr) return;
  for (int j = 0; j < nb; ++j)
    for (int i = std::max(0, j - ku); i < std::min(nb, j + ku + 1); ++i)
      jac->at(i, j) += beta * tm.cv * k0.at(i, j);
  double vmax = 0.0, ymax = 0.0;
  for (int i = 0; i < nb; ++i) {
    vmax = std::max(vmax, std::abs(v[i]));
    ymax = std::max(ymax, std::abs(y[i]));
  }
  if (vmax == 0.0 || tm.ck == 0.0) return;
  const double h = 6e-6 * (1.0 + ymax) / vmax;
  kb.assign(size, 0.0);
  kp.assign(size, 0.0);
  ys.resize(sz(nb));
  const BandView km = numpy_band(kb.data(), nb, ku), kpv = numpy_band(kp.data(), nb, ku);
  for (int i = 0; i < nb; ++i) ys[sz(i)] = y[i] + h * v[i];
  assemble(mod, ys.data(), f.data(), &kpv, 1.0);
  for (int i = 0; i < nb; ++i) ys[sz(i)] = y[i] - h * v[i];
  assemble(mod, ys.data(), f.data(), &km, 1.0);
  const double scale = beta * tm.ck / (2.0 * h);
  for (int j = 0; j < nb; ++j)
    for (int i = std::max(0, j - ku); i < std::min(nb, j + ku + 1); ++i)
      jac->at(i, j) += scale * (kpv.at(i, j) - km.at(i, j));
}

}  // namespace

void constraints(const System& s, const double* y, double t, double* g, const double* lam) {
  for (std::size_t k = 0; k < s.joints.size(); ++k) {
    const JointData& jd = s.joints[k];
    if (jd.info.kind == JointKind::sliding) {
      const int row0 = s.joint_row[k];
      g[row0 + s.dim] = 0.0;
      if (lam == nullptr) throw std::invalid_argument("constraints: a sliding joint needs lam");
      sliding_rows(s, jd, y, t, lam[row0 + s.dim], g + row0);
      continue;
    }
    const PlaceRef &pa = s.places[sz(jd.a)], &pb = s.places[sz(jd.b)];
    PlaceEval ea, eb;
    place_at(s, pa, s.maps[sz(jd.a)], t, y, ea);
    place_at(s, pb, s.maps[sz(jd.b)], t, y, eb);
    const double th = jd.angle >= 0 ? evaluate(s.tfs[sz(jd.angle)], 0, t).f : 0.0;
    double jac[kMaxJointRows * 2 * kMaxLocal];
    eval_joint(jd.info, ea, eb, th, g + s.joint_row[k], jac);
  }
  for (std::size_t r = 0; r < s.rigid.size(); ++r) {
    if (s.norm_row[r] < 0) continue;
    const double* p = y + s.rigid_offset(static_cast<int>(r)) + 3;
    g[s.norm_row[r]] = 0.5 * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0);
  }
  std::fill(g + s.linear_row, g + s.linear_row + s.n_linear, 0.0);
  for (const LinearTerm& lt : s.linear) g[s.linear_row + lt.row] += lt.coef * y[lt.col];
}

namespace {

/// The arguments of assemble_system, and what its stages share: the far entries of the Jacobian.
struct Stage {
  const System& s;
  const double *yf, *vf, *am, *lam, *y1;
  const AssemblyTerms& tm;
  double* r;
  BorderedLU* lu;
  Far& far;
};

/// A driven drum's coupling to its line (its row goes into the border).
struct DrumRow {
  int offset, drum;  // the line's first coordinate, the drum's
  DrumTerms terms;
};

/// Each joint's Jacobian of its rows over its places' local coordinates.
using JointJacobians = std::vector<std::array<double, kMaxJointRows * 2 * kMaxLocal>>;

/// Flexible bodies: elements, loads, constant mass, rotary inertia, fluid, winches and drums.
void flexible_terms(const Stage& st, std::vector<DrumRow>& drums) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const double c = s.damping;
  thread_local std::vector<double> f, g, acc, mv, fl, dfrow;  // work arrays, kept between calls
  thread_local ScaledBody scaled;                             // a winch's body at its length L(t)
  const bool moving = am != nullptr && !tm.statics;           // a drum's rates count
  for (std::size_t b = 0; b < s.flex.size(); ++b) {
    const Winch* win = winch_of(s, b);
    const WinchState ws = win != nullptr ? winch_state(s, *win, tm.tf, yf, moving ? vf : nullptr,
                                                       moving ? am : nullptr)
                                         : WinchState{};
    const Model& mod = win != nullptr ? scaled_model(*s.flex[b], ws.ratio, scaled) : *s.flex[b];
    const int o = s.offset[b], nb = mod.n(), ku = mod.ku();
    f.assign(sz(nb), 0.0);
    g.assign(sz(nb), 0.0);
    BandView jac{nullptr, 0, 0, 0};
    if (lu != nullptr) jac = lu->block(static_cast<int>(b));
    // no element tangents where they count zero times (the mass matrix of a = M^-1 F)
    assemble(mod, yf + o, f.data(), lu != nullptr && tm.ck != 0.0 ? &jac : nullptr, tm.ck);
    if (tm.distributed_only)  // the weight only, not the point loads
      std::copy(mod.loads.f_gravity, mod.loads.f_gravity + nb, g.begin());
    else
      external_force(mod, tm.tf, yf + o, g.data(), tm.amplitude);
    if (lu != nullptr && mod.loads.n_moment > 0)
      subtract_load_stiffness(mod, tm.tf, yf + o, jac, tm.ck * tm.load_factor, tm.amplitude);
    for (int i = 0; i < nb; ++i) r[o + i] += f[sz(i)] - tm.load_factor * g[sz(i)];
    if (tm.internal != nullptr) std::copy(f.begin(), f.end(), tm.internal + o);
    if (tm.own != nullptr)  // the point loads taken back out (added to r below)
      for (int i = 0; i < nb; ++i)
        tm.own[o + i] =
            tm.distributed_only ? 0.0 : tm.load_factor * (g[sz(i)] - mod.loads.f_gravity[i]);
    // a driven drum's share of its line's fluid loads: the line's rows (fl, for the drum's
    // column: every term is proportional to L) and the drum's residual and row
    const bool drum_fluid = win != nullptr && win->drum >= 0 && !win->convective.empty();
    DrumFluid dfl{drum_fluid ? win->convective.data() : nullptr, 0.0, nullptr};
    fl.assign(drum_fluid ? sz(nb) : 0, 0.0);
    dfrow.assign(drum_fluid && lu != nullptr ? sz(nb) : 0, 0.0);
    if (drum_fluid && lu != nullptr) dfl.row = dfrow.data();
    if (s.fluid != nullptr) {  // buoyancy, Morison loads, distributed loads (fluid.hpp)
      const LineTerms lt{tm.tf,          tm.ck,  tm.cv,    tm.ca,
                         tm.load_factor, &s.tfs, ws.ratio, drum_fluid ? &dfl : nullptr};
      for (const LineFluid& ln : s.fluid->lines)
        if (ln.body == static_cast<int>(b))
          assemble_line(mod, *s.fluid, ln, yf + o, am != nullptr ? vf + o : nullptr,
                        am != nullptr ? am + o : nullptr, lt, drum_fluid ? fl.data() : r + o,
                        lu != nullptr ? &jac : nullptr, nullptr);
      for (std::size_t i = 0; i < fl.size(); ++i) r[o + static_cast<int>(i)] += fl[i];
    }
    if (am != nullptr) {  // M (am + c vf)
      acc.resize(sz(nb));
      mv.resize(sz(nb));
      for (int i = 0; i < nb; ++i) acc[sz(i)] = am[o + i] + c * vf[o + i];
      band_matvec(mod.mass_band, acc.data(), nb, ku, mv.data());
      for (int i = 0; i < nb; ++i) r[o + i] += mv[sz(i)];
      if (lu != nullptr) {
        const double cm = tm.ca + c * tm.cv;
        for (int j = 0; j < nb; ++j)
          for (int i = std::max(0, j - ku); i < std::min(nb, j + ku + 1); ++i)
            jac.at(i, j) += cm * mod.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * nb + j];
      }
      if (win != nullptr && !tm.statics)  // the material moving through the mesh
        winch_inertia(*win, ws, yf + o, vf + o, tm.ck, tm.cv, r + o,
                      lu != nullptr ? &jac : nullptr);
      if (has_rotary_inertia(mod))
        assemble_inertia(mod, yf + o, vf + o, am + o, {c, tm.ck, tm.cv, tm.ca}, r + o,
                         lu != nullptr ? &jac : nullptr);
      if (!tm.statics && vf != nullptr)  // Kelvin-Voigt strain-rate damping, if the body has it
        assemble_damping(mod, yf + o, vf + o, tm.ck, tm.cv, r + o, lu != nullptr ? &jac : nullptr);
      if (s.stiffness_damping > 0.0 && vf != nullptr)
        stiffness_damping(mod, s.stiffness_damping, yf + o, vf + o, tm, r + o,
                          lu != nullptr ? &jac : nullptr);
    }
    if (win != nullptr && win->drum >= 0) {  // a driven drum: its row, its coupling
      DrumTerms dt;
      const double torque = evaluate(s.tfs[sz(win->torque)], 0, tm.tf).f;
      drum_terms(*s.flex[b], mod, *win, ws, yf + o, moving ? vf + o : nullptr,
                 moving ? am + o : nullptr, torque, tm.load_factor, c, tm.ck, tm.cv, tm.ca,
                 lu != nullptr, dt);
      dt.residual += dfl.residual;
      for (std::size_t i = 0; i < dfrow.size(); ++i) {  // (variable-length.md §3.5)
        dt.row[i] += dfrow[i];
        dt.col[i] += tm.ck * fl[i] / ws.length;
      }
      r[win->drum] += dt.residual;
      if (lu != nullptr) {
        for (int i = 0; i < nb; ++i)
          if (dt.col[sz(i)] != 0.0) far.add(o + i, win->drum, dt.col[sz(i)]);
        lu->block(lu->block_of(win->drum)).at(0, 0) = dt.diag;  // the drum's own block
        drums.push_back({o, win->drum, std::move(dt)});
      }
    }
  }
}

/// Rigid bodies and point masses: inertia, damping, gravity.
void rigid_terms(const Stage& st) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const double c = s.damping;
  for (std::size_t k = 0; k < s.rigid.size(); ++k) {
    const RigidInertia& body = s.rigid[k];
    const int o = s.rigid_offset(static_cast<int>(k)), nb = rigid_size(body);
    const int bi = static_cast<int>(s.flex.size() + k);
    std::array<double, 49> kk;
    std::fill(kk.begin(), kk.begin() + nb * nb, 0.0);
    BandView jac{nullptr, 0, 0, 0};
    if (lu != nullptr) jac = lu->block(bi);
    if (am != nullptr) {
      std::array<double, 7> fr{};
      rigid_inertial_force(body, yf + o, vf + o, am + o, tm.ck, tm.cv, tm.ca, fr.data(),
                           lu != nullptr ? kk.data() : nullptr);
      const int nd = body.point_mass ? body.dim : (body.dim == 2 ? 3 : 3);  // damped coordinates
      for (int i = 0; i < nb; ++i) r[o + i] += fr[sz(i)];
      for (int i = 0; i < nd; ++i) {
        const double mi =
            (body.dim == 2 && !body.point_mass && i == 2) ? body.inertia[0] : body.mass;
        r[o + i] += c * mi * vf[o + i];
        kk[sz(i * nb + i)] += tm.cv * c * mi;
      }
    }
    const int nt = body.point_mass ? body.dim : (body.dim == 2 ? 2 : 3);
    for (int i = 0; i < nt; ++i) r[o + i] -= tm.load_factor * body.mass * s.gravity[i];
    if (lu != nullptr)
      for (int i = 0; i < nb; ++i)
        for (int j = 0; j < nb; ++j)
          if (std::abs(i - j) <= lu->block_ku(bi)) jac.at(i, j) += kk[sz(i * nb + j)];
  }
}

/// Loads at places (forces, and torques on rigid bodies).
void load_terms(const Stage& st) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  for (const PlaceLoad& ld : s.loads) {
    if (tm.distributed_only) break;
    const PlaceRef& p = s.places[sz(ld.place)];
    const PlaceMap& map = s.maps[sz(ld.place)];
    const double fac =
        tm.load_factor * (ld.factor >= 0 ? evaluate(s.tfs[sz(ld.factor)], 0, tm.tf).f : 1.0);
    double F[3], T[3], u[kMaxLocal], q[kMaxLocal];
    for (int i = 0; i < 3; ++i) {
      F[i] = fac * ld.force[i];
      T[i] = fac * ld.torque[i];
    }
    const bool torque = T[0] != 0.0 || T[1] != 0.0 || T[2] != 0.0;
    auto gen = [&](double* out) {
      PlaceEval e;
      place_local(s, p, map, tm.tf, u, e);
      place_force(e, F, torque ? T : nullptr, s.dim, out, p.kind == PlaceKind::rigid3d);
    };
    gather(map, yf, u);
    gen(q);
    for (int j = 0; j < map.n; ++j) r[map.index[j]] -= q[j];
    const bool turns = p.kind == PlaceKind::rigid2d || p.kind == PlaceKind::rigid3d ||
                       (torque && p.kind == PlaceKind::rod);
    if (lu != nullptr && turns) {
      std::array<double, kMaxLocal * kMaxLocal> K{};
      jacobian_fd(map.n, u, gen, K.data());
      for (double& v : K) v *= -tm.ck;
      add_matrix(*lu, map.index, map.n, K.data(), far);
    }
  }
}

/// A spring's elastic tension T and dT/dl at the length len: k (len - length), or its law's.
LawValue spring_tension(const System& s, const SpringData& sp, double len) {
  if (sp.law < 0) return {sp.stiffness * (len - sp.length), sp.stiffness};
  return spring_law(s.tfs[sz(sp.law)], len - sp.length);
}

/// Springs between two places.
void spring_terms(const Stage& st) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  for (const SpringData& sp : s.springs) {
    if (tm.distributed_only) break;
    const PlaceRef &pa = s.places[sz(sp.a)], &pb = s.places[sz(sp.b)];
    const PlaceMap &ma = s.maps[sz(sp.a)], &mb = s.maps[sz(sp.b)];
    const int k = ma.n + mb.n;
    // a spring of zero rest length is the linear spring-damper F = k (x_a - x_b) + c (v_a - v_b),
    // whose axial form k l e has no direction where the places meet (a spring to ground)
    const bool linear = sp.length == 0.0;
    std::array<double, 2 * kMaxLocal> u{}, w{};
    gather(ma, yf, u.data());
    gather(mb, yf, u.data() + ma.n);
    if (vf != nullptr) {
      gather(ma, vf, w.data());
      gather(mb, vf, w.data() + ma.n);
    }
    auto force = [&](double* out) {
      PlaceEval ea, eb;
      place_local(s, pa, ma, tm.tf, u.data(), ea);
      place_local(s, pb, mb, tm.tf, u.data() + ma.n, eb);
      double d[3], len = 0.0, rate = 0.0;
      for (int i = 0; i < 3; ++i) {
        d[i] = ea.x[i] - eb.x[i];
        len += d[i] * d[i];
      }
      len = std::sqrt(len);
      double dvel[3];
      for (int i = 0; i < 3; ++i) {
        double va = 0.0, vb = 0.0;
        for (int j = 0; j < ea.n; ++j) va += ea.dx[i][j] * w[sz(j)];
        for (int j = 0; j < eb.n; ++j) vb += eb.dx[i][j] * w[sz(ma.n + j)];
        dvel[i] = va - vb;
        if (!linear) rate += d[i] / len * dvel[i];
      }
      const double tension = linear ? 0.0 : spring_tension(s, sp, len).t + sp.damping * rate;
      double F[3];
      for (int i = 0; i < 3; ++i)  // zero rest length: F = k d + c dv (no direction needed)
        F[i] = linear ? sp.stiffness * d[i] + sp.damping * dvel[i] : tension * d[i] / len;
      place_force(ea, F, nullptr, s.dim, out, false);  // on A: +T e (the spring pulls A back)
      for (int i = 0; i < 3; ++i) F[i] = -F[i];
      place_force(eb, F, nullptr, s.dim, out + ma.n, false);
    };
    std::array<double, 2 * kMaxLocal> fs{};
    force(fs.data());
    int idx[2 * kMaxLocal];
    for (int j = 0; j < ma.n; ++j) idx[j] = ma.index[j];
    for (int j = 0; j < mb.n; ++j) idx[ma.n + j] = mb.index[j];
    for (int j = 0; j < k; ++j) r[idx[j]] += fs[sz(j)];
    if (lu != nullptr) {
      // exact where the places' positions are linear in their coordinates:
      // dF/dx_a = k e e^T + T/l (I - e e^T) + c e (dv_perp)^T / l, dF/dv_a = c e e^T, with
      // J = [dx_a, -dx_b] the generalized forces' map: K = J^T (ck dF/dx + cv dF/dv) J;
      // the columns of rotation-like coordinates (the places' curvature) by central differences
      PlaceEval ea, eb;
      place_local(s, pa, ma, tm.tf, u.data(), ea);
      place_local(s, pb, mb, tm.tf, u.data() + ma.n, eb);
      double J[3][2 * kMaxLocal] = {}, d[3], dv[3] = {0.0, 0.0, 0.0}, len = 0.0;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < ma.n; ++j) J[i][j] = ea.dx[i][j];
        for (int j = 0; j < mb.n; ++j) J[i][ma.n + j] = -eb.dx[i][j];
        d[i] = ea.x[i] - eb.x[i];
        len += d[i] * d[i];
        for (int j = 0; j < k; ++j) dv[i] += J[i][j] * w[sz(j)];
      }
      len = std::sqrt(len);
      double e[3] = {0.0, 0.0, 0.0}, rate = 0.0;
      for (int i = 0; i < 3 && !linear; ++i) {
        e[i] = d[i] / len;
        rate += e[i] * dv[i];
      }
      const LawValue law = linear ? LawValue{0.0, sp.stiffness} : spring_tension(s, sp, len);
      const double tension = linear ? 0.0 : law.t + sp.damping * rate;
      double A[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double id = i == j ? 1.0 : 0.0;
          if (linear) {
            A[i][j] = (tm.ck * sp.stiffness + tm.cv * sp.damping) * id;
            continue;
          }
          const double perp = id - e[i] * e[j];
          const double dvp = dv[j] - rate * e[j];  // (I - e e^T) dv
          A[i][j] = tm.ck * (law.dt * e[i] * e[j] + tension / len * perp +
                             sp.damping * e[i] * dvp / len) +
                    tm.cv * sp.damping * e[i] * e[j];
        }
      std::vector<double> K(sz(k * k), 0.0);
      for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
          double v = 0.0;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) v += J[i][a] * A[i][j] * J[j][b];
          K[sz(a * k + b)] = v;
        }
      bool vary[2 * kMaxLocal], any = false;
      for (int a = 0; a < k; ++a) {
        vary[a] = a < ma.n ? nonlinear_local(pa.kind, s.dim, a)
                           : nonlinear_local(pb.kind, s.dim, a - ma.n);
        any = any || vary[a];
      }
      if (any) {
        std::vector<double> Kfd(sz(k * k));
        jacobian_fd(k, u.data(), force, Kfd.data(), vary);
        for (int a = 0; a < k; ++a)
          for (int b = 0; b < k; ++b)
            if (vary[b]) {
              double kv = 0.0;  // the velocity part of column b stays exact
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                  kv += J[i][a] * tm.cv * sp.damping *
                        (linear ? (i == j ? 1.0 : 0.0) : e[i] * e[j]) * J[j][b];
              K[sz(a * k + b)] = tm.ck * Kfd[sz(a * k + b)] + kv;
            }
      }
      add_matrix(*lu, idx, k, K.data(), far);
    }
  }
}

/// Contact with obstacles (contact.hpp); its forces are the bodies' own terms too.
void contact_terms(const Stage& st) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const int n = s.n;
  thread_local std::vector<double> before;
  const bool rescaled = tm.contact_step && tm.contact_scale != 1.0;
  if ((tm.own != nullptr || rescaled) && s.contact != nullptr) before.assign(r, r + n);
  if (s.contact != nullptr && tm.skip_contact) {
    // the residual without contact (the step's start, time-integration.md sec. 4)
  } else if (s.contact != nullptr && tm.contact_step) {  // a step's: at its alpha point
    const MatrixSink sink = [&](const int* idx, int k, const double* K) {
      add_matrix(*lu, idx, k, K, far);
    };
    assemble_contact(s, *s.contact, tm.contact_yf, tm.contact_vf, y1, tm, r, lu,
                     lu != nullptr ? &sink : nullptr);
    if (rescaled)
      for (int i = 0; i < n; ++i) r[i] = before[sz(i)] + tm.contact_scale * (r[i] - before[sz(i)]);
  } else if (s.contact != nullptr && tm.contact_yf != nullptr) {  // forces of another state
    assemble_contact(s, *s.contact, tm.contact_yf, tm.contact_vf, tm.contact_y1, tm, r, nullptr,
                     nullptr);
  } else if (s.contact != nullptr) {
    const MatrixSink sink = [&](const int* idx, int k, const double* K) {
      add_matrix(*lu, idx, k, K, far);
    };
    assemble_contact(s, *s.contact, yf, vf, y1, tm, r, lu, lu != nullptr ? &sink : nullptr);
  }
  if (tm.own != nullptr && s.contact != nullptr)
    for (int i = 0; i < n; ++i) tm.own[i] += r[i] - before[sz(i)];
}

/// Joints: G(yf)^T lambda, g(y1), and their derivatives (the Jacobians kept for the border).
void joint_terms(const Stage& st, JointJacobians& jac1, JointJacobians& jacf) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const int n = s.n;
  const MatrixSink joint_sink = [&](const int* idx, int k, const double* K) {
    add_matrix(*lu, idx, k, K, far);
  };
  for (std::size_t jj = 0; jj < s.joints.size(); ++jj) {
    if (tm.distributed_only) break;  // no joint forces (nor their rows)
    const JointData& jd = s.joints[jj];
    if (jd.info.kind == JointKind::sliding) {
      sliding_residual(s, jj, yf, lam, y1, tm, r, lu != nullptr ? &joint_sink : nullptr);
      continue;
    }
    const PlaceRef &pa = s.places[sz(jd.a)], &pb = s.places[sz(jd.b)];
    const PlaceMap &ma = s.maps[sz(jd.a)], &mb = s.maps[sz(jd.b)];
    const int rows = joint_rows(jd.info), row0 = s.joint_row[jj], k = ma.n + mb.n;
    std::array<double, 2 * kMaxLocal> u;  // the first k set below (no clearing of all 48)
    const bool frames = !(jd.info.kind == JointKind::pin && !jd.info.driven);  // a pin: none
    auto eval_at = [&](const double* uu, double t, double* gg, double* jac) {  // jac null: g
      PlaceEval ea, eb;
      place_local(s, pa, ma, t, uu, ea, frames);
      place_local(s, pb, mb, t, uu + ma.n, eb, frames);
      const double th = jd.angle >= 0 ? evaluate(s.tfs[sz(jd.angle)], 0, t).f : 0.0;
      eval_joint(jd.info, ea, eb, th, gg, jac);
    };
    double gtmp[kMaxJointRows];
    gather(ma, y1, u.data());
    gather(mb, y1, u.data() + ma.n);
    // g(y1); its Jacobian (the border's Q) only for a matrix
    eval_at(u.data(), tm.t1, r + n + row0, lu != nullptr ? jac1[jj].data() : nullptr);
    gather(ma, yf, u.data());
    gather(mb, yf, u.data() + ma.n);
    eval_at(u.data(), tm.tf, gtmp, jacf[jj].data());
    const double* lj = lam + row0;
    auto gtl = [&](double* out) {  // G(u)^T lambda
      double gg[kMaxJointRows], jac[kMaxJointRows * 2 * kMaxLocal];
      eval_at(u.data(), tm.tf, gg, jac);
      for (int a = 0; a < k; ++a) {
        out[a] = 0.0;
        for (int q = 0; q < rows; ++q) out[a] += jac[q * k + a] * lj[q];
      }
    };
    std::array<double, 2 * kMaxLocal> gl;
    std::fill(gl.begin(), gl.begin() + k, 0.0);
    for (int a = 0; a < k; ++a)  // G(yf)^T lambda from the evaluation at yf above
      for (int q = 0; q < rows; ++q) gl[sz(a)] += jacf[jj][sz(q * k + a)] * lj[q];
    int idx[2 * kMaxLocal];
    for (int j = 0; j < ma.n; ++j) idx[j] = ma.index[j];
    for (int j = 0; j < mb.n; ++j) idx[ma.n + j] = mb.index[j];
    for (int a = 0; a < k; ++a) r[idx[a]] += gl[sz(a)];
    if (lu != nullptr) {
      // d(G^T lambda)/du: only rotation-like coordinates change G (a pin or slider between
      // places whose positions are linear in their coordinates has none: skipped)
      bool vary[2 * kMaxLocal], any = false;
      for (int a = 0; a < k; ++a) {
        vary[a] = a < ma.n ? ma.reduced || nonlinear_local(pa.kind, s.dim, a)
                           : mb.reduced || nonlinear_local(pb.kind, s.dim, a - ma.n);
        any = any || vary[a];
      }
      bool lam_nonzero = false;
      for (int q = 0; q < rows; ++q) lam_nonzero = lam_nonzero || lj[q] != 0.0;
      const bool pinlike = jd.info.kind == JointKind::pin && !jd.info.driven;
      const bool rigid = pa.kind == PlaceKind::rigid2d || pa.kind == PlaceKind::rigid3d ||
                         pb.kind == PlaceKind::rigid2d || pb.kind == PlaceKind::rigid3d;
      if (any && lam_nonzero && (!pinlike || rigid)) {
        double K[4 * kMaxLocal * kMaxLocal];
        jacobian_fd(k, u.data(), gtl, K, vary);
        // lambda^T g'' is symmetric: the columns of positions (not differenced) from the rows;
        // positions enter the joint rows at most linearly, so their block is zero
        for (int a = 0; a < k; ++a)
          for (int b = 0; b < k; ++b)
            if (!vary[b]) K[a * k + b] = vary[a] ? K[b * k + a] : 0.0;
        for (int i = 0; i < k * k; ++i) K[i] *= tm.ck;
        add_matrix(*lu, idx, k, K, far);
      }
    }
  }
}

/// Quaternion normalization rows of rigid bodies, and the linear rows g = A y1.
void normalization_terms(const Stage& st) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const int n = s.n;
  for (std::size_t b = 0; b < s.rigid.size(); ++b) {  // quaternion normalization
    if (s.norm_row[b] < 0) continue;
    const int o = s.rigid_offset(static_cast<int>(b)) + 3, row = s.norm_row[b];
    const double* p1 = y1 + o;
    r[n + row] = 0.5 * (p1[0] * p1[0] + p1[1] * p1[1] + p1[2] * p1[2] + p1[3] * p1[3] - 1.0);
    for (int i = 0; i < 4; ++i) r[o + i] += yf[o + i] * lam[row];
    if (lu != nullptr) {
      const int bi = static_cast<int>(s.flex.size() + b);
      for (int i = 0; i < 4; ++i) lu->view(bi).at(3 + i, 3 + i) += tm.ck * lam[row];
    }
  }
  for (const LinearTerm& t : s.linear) {  // linear rows: g = A y1, A^T lambda
    r[n + s.linear_row + t.row] += t.coef * y1[t.col];
    r[t.col] += t.coef * lam[s.linear_row + t.row];
  }
}

/// The border: multipliers (m), then the drums'; the far entries to the solver (its border's
/// unknowns or a reordered band: bordered.hpp).
void border_terms(const Stage& st, const std::vector<DrumRow>& drums, const JointJacobians& jac1,
                  const JointJacobians& jacf) {
  const auto& [s, yf, vf, am, lam, y1, tm, r, lu, far] = st;  // what this stage reads
  const int m = s.m;
  lu->reset_border(m + static_cast<int>(drums.size()));
  lu->swap_far(far.entries);
  for (std::size_t jj = 0; jj < s.joints.size(); ++jj) {
    const JointData& jd = s.joints[jj];
    if (jd.info.kind == JointKind::sliding) {
      sliding_border(s, jj, yf, lam, y1, tm, *lu);
      continue;
    }
    const PlaceMap &ma = s.maps[sz(jd.a)], &mb = s.maps[sz(jd.b)];
    const int rows = joint_rows(jd.info), row0 = s.joint_row[jj], k = ma.n + mb.n;
    for (int q = 0; q < rows; ++q)
      for (int a = 0; a < k; ++a) {
        const int gi = a < ma.n ? ma.index[a] : mb.index[a - ma.n];
        lu->add_p(row0 + q, gi, jacf[jj][sz(q * k + a)]);
        lu->add_q(row0 + q, gi, jac1[jj][sz(q * k + a)]);
      }
  }
  for (std::size_t b = 0; b < s.rigid.size(); ++b) {
    if (s.norm_row[b] < 0) continue;
    const int o = s.rigid_offset(static_cast<int>(b)) + 3, row = s.norm_row[b];
    for (int i = 0; i < 4; ++i) {
      lu->add_p(row, o + i, yf[o + i]);
      lu->add_q(row, o + i, y1[o + i]);
    }
  }
  for (const LinearTerm& t : s.linear) {
    lu->add_p(s.linear_row + t.row, t.col, t.coef);
    lu->add_q(s.linear_row + t.row, t.col, t.coef);
  }
  int z = m;
  // a drum's row by the line's coordinates: w = row . x, Q[w] = row, D = -1, P[drum][w] = 1
  for (const DrumRow& d : drums) {
    for (std::size_t i = 0; i < d.terms.row.size(); ++i)
      lu->add_q(z, d.offset + static_cast<int>(i), d.terms.row[i]);
    lu->add_p(z, d.drum, 1.0);
    lu->add_d(z, z, -1.0);
    ++z;
  }
}

}  // namespace

bool assemble_system(const System& s, const double* yf, const double* vf, const double* am,
                     const double* lam, const double* y1, const AssemblyTerms& tm, double* r,
                     BorderedLU* lu) {
  const int n = s.n, m = s.m;
  std::fill(r, r + n + m, 0.0);
  if (tm.own != nullptr) std::fill(tm.own, tm.own + n, 0.0);
  thread_local Far far;
  far.entries.clear();
  const Stage st{s, yf, vf, am, lam, y1, tm, r, lu, far};
  thread_local std::vector<DrumRow> drums;
  drums.clear();
  flexible_terms(st, drums);
  rigid_terms(st);
  if (tm.own != nullptr)  // the bodies' own terms so far: elements, weight, inertia, fluid
    for (int i = 0; i < n; ++i) tm.own[i] += r[i];
  load_terms(st);
  spring_terms(st);
  contact_terms(st);
  thread_local JointJacobians jac1, jacf;
  jac1.resize(s.joints.size());
  jacf.resize(s.joints.size());
  joint_terms(st, jac1, jacf);
  normalization_terms(st);
  for (int i = 0; i < n + m; ++i)
    if (!std::isfinite(r[i])) return false;
  if (lu == nullptr) return true;
  border_terms(st, drums, jac1, jacf);
  return true;
}

void fluid_forces(const System& s, const double* y, const double* v, const double* a, double t,
                  double* out) {
  std::fill(out, out + 3 * s.flex.size(), 0.0);
  if (s.fluid == nullptr) return;
  std::vector<double> r;
  LineTerms lt{t, 1.0, 0.0, 0.0, 1.0, &s.tfs};
  for (const LineFluid& ln : s.fluid->lines) {
    const std::size_t b = sz(ln.body);
    const int o = s.offset[b];
    const Winch* win = winch_of(s, b);  // a winch's line: its terms at its length L(t)
    lt.length_ratio = win != nullptr ? winch_state(s, *win, t, y).ratio : 1.0;
    r.assign(sz(s.flex[b]->n()), 0.0);
    assemble_line(*s.flex[b], *s.fluid, ln, y + o, a != nullptr ? v + o : nullptr,
                  a != nullptr ? a + o : nullptr, lt, r.data(), nullptr, out + 3 * b);
  }
}

}  // namespace rancf
