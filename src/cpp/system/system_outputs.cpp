// Joint reactions from the multipliers (system.hpp: joint_reaction).
#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/system_integrator.hpp"
#include "system/system.hpp"
#include "system/winch.hpp"

namespace rancf {

namespace {
std::size_t sz(int i) { return static_cast<std::size_t>(i); }

/// Solve the symmetric k x k system A x = b (k <= 6) by Gaussian elimination with partial
/// pivoting; rows whose pivot vanishes leave their unknown zero.
void solve_small(int k, double (*A)[6], double* b, double* x) {
  int perm[6];
  for (int i = 0; i < k; ++i) perm[i] = i;
  double scale = 0.0;
  for (int i = 0; i < k; ++i) scale = std::max(scale, std::abs(A[i][i]));
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int r = c + 1; r < k; ++r)
      if (std::abs(A[r][c]) > std::abs(A[p][c])) p = r;
    std::swap(A[c], A[p]);
    std::swap(b[c], b[p]);
    std::swap(perm[c], perm[p]);
    if (std::abs(A[c][c]) <= 1e-14 * scale) continue;
    for (int r = c + 1; r < k; ++r) {
      const double l = A[r][c] / A[c][c];
      for (int j = c; j < k; ++j) A[r][j] -= l * A[c][j];
      b[r] -= l * b[c];
    }
  }
  for (int c = k - 1; c >= 0; --c) {
    double v = b[c];
    for (int j = c + 1; j < k; ++j) v -= A[c][j] * x[j];
    x[c] = std::abs(A[c][c]) <= 1e-14 * scale ? 0.0 : v / A[c][c];
  }
  (void)perm;
}
}  // namespace

void joint_reaction(const System& s, int k, const double* y, double t, const double* lam,
                    double* force, double* moment) {
  const JointData& jd = s.joints[sz(k)];
  if (jd.info.kind == JointKind::sliding) {  // on the body's point: -lambda, no moment
    for (int i = 0; i < 3; ++i) {
      force[i] = i < s.dim ? -lam[s.joint_row[sz(k)] + i] : 0.0;
      moment[i] = 0.0;
    }
    return;
  }
  const PlaceRef &pa = s.places[sz(jd.a)], &pb = s.places[sz(jd.b)];
  PlaceEval ea, eb;
  place_at(s, pa, s.maps[sz(jd.a)], t, y, ea);
  place_at(s, pb, s.maps[sz(jd.b)], t, y, eb);
  const double th = jd.angle >= 0 ? evaluate(s.tfs[sz(jd.angle)], 0, t).f : 0.0;
  const int rows = joint_rows(jd.info), w = ea.n + eb.n;
  double g[kMaxJointRows], jac[kMaxJointRows * 2 * kMaxLocal];
  eval_joint(jd.info, ea, eb, th, g, jac);
  const double* l = lam + s.joint_row[sz(k)];
  double q[kMaxLocal] = {};  // Q = -G_A^T lambda
  for (int j = 0; j < ea.n; ++j)
    for (int r = 0; r < rows; ++r) q[j] -= jac[r * w + j] * l[r];
  // basis vectors per coordinate: [dx/du_j ; w_j]
  double b[kMaxLocal][6] = {};
  for (int j = 0; j < ea.n; ++j) {
    for (int i = 0; i < 3; ++i) b[j][i] = ea.dx[i][j];
    if (ea.nf == 3) {
      for (int f = 0; f < 3; ++f) {
        const double* v = ea.f[f];
        const double d[3] = {ea.df[f][0][j], ea.df[f][1][j], ea.df[f][2][j]};
        b[j][3] += 0.5 * (v[1] * d[2] - v[2] * d[1]);
        b[j][4] += 0.5 * (v[2] * d[0] - v[0] * d[2]);
        b[j][5] += 0.5 * (v[0] * d[1] - v[1] * d[0]);
      }
    } else if (ea.nf == 1) {  // a 3D cable: its tangent turns by t x dt
      const double* v = ea.f[0];
      const double d0[3] = {ea.df[0][0][j], ea.df[0][1][j], ea.df[0][2][j]};
      b[j][3] = v[1] * d0[2] - v[2] * d0[1];
      b[j][4] = v[2] * d0[0] - v[0] * d0[2];
      b[j][5] = v[0] * d0[1] - v[1] * d0[0];
    }
  }
  double A[6][6] = {}, rhs[6] = {}, x[6] = {};
  for (int j = 0; j < ea.n; ++j)
    for (int a = 0; a < 6; ++a) {
      rhs[a] += b[j][a] * q[j];
      for (int c = 0; c < 6; ++c) A[a][c] += b[j][a] * b[j][c];
    }
  solve_small(6, A, rhs, x);
  for (int i = 0; i < 3; ++i) {
    force[i] = x[i];
    moment[i] = x[3 + i];
  }
}

void SystemIntegrator::derived_rows(int k, const double* t, const double* y, const double* v,
                                    double* a, double* lam, double* res, double* joints,
                                    double* res0, double* internal, const double* alpha) {
  const auto n = sz(s_.n), m = sz(s_.m), nj = s_.joints.size();
  // where the balance is M a + (terms without a), M constant (no constraints, rigid bodies,
  // rotary inertia, contact, fluid or winches), the residual at the consistent a is that of
  // initial_acceleration's assembly (at the known a) plus M (a - a_known): no second assembly;
  // the bodies' own terms and the element forces come from the same assembly
  bool linear = mass_constant_ && s_.fluid == nullptr;
  for (std::size_t b = 0; b < s_.flex.size(); ++b) linear = linear && winch_of(s_, b) == nullptr;
  std::vector<double> md;
  for (std::size_t i = 0; i < sz(k); ++i) {
    const double *yi = y + i * n, *vi = v + i * n;
    double *ai = a + i * n, *li = lam + i * m, *ri = res + i * (n + m);
    double* oi = res0 != nullptr ? res0 + i * n : nullptr;
    double* fi = internal != nullptr ? internal + i * n : nullptr;
    std::fill(ai, ai + n, 0.0);
    std::fill(li, li + m, 0.0);
    // contact: the forces of the step that ended at the row, at its alpha point (yf, vf) and
    // end (the row); without alpha a step of length zero (the row's own state)
    AssemblyTerms step;
    if (s_.contact != nullptr) {
      step.contact_yf = alpha != nullptr ? alpha + i * 2 * n : yi;
      step.contact_vf = alpha != nullptr ? alpha + i * 2 * n + n : vi;
      step.contact_y1 = yi;
    }
    AssemblyTerms outs = step;  // the same pass's element forces and own terms (linear: at
    outs.internal = fi;         // a_known)
    outs.own = oi;
    const AssemblyTerms* first = linear ? &outs : s_.contact != nullptr ? &step : nullptr;
    if (initial_acceleration(yi, vi, t[i], ai, li, first) && linear) {
      std::copy(r_.begin(), r_.begin() + static_cast<std::ptrdiff_t>(n), ri);
      for (std::size_t b = 0; b < s_.flex.size(); ++b) {  // + M dz, dz = a - a_known
        const Model& mod = *s_.flex[b];
        const int o = s_.offset[b], nb = mod.n();
        md.resize(sz(nb));
        band_matvec(mod.mass_band, dz_.data() + o, nb, mod.ku(), md.data());
        for (int j = 0; j < nb; ++j) ri[o + j] += md[sz(j)];
        if (oi != nullptr)
          for (int j = 0; j < nb; ++j) oi[o + j] += md[sz(j)];
      }
    } else {
      AssemblyTerms terms = step;  // the balance residual at (y, v, a, lambda, t), as
      terms.tf = terms.t1 = t[i];  // System.residual
      terms.internal = fi;
      terms.own = oi;
      assemble_system(s_, yi, vi, ai, li, yi, terms, ri, nullptr);
    }
    for (std::size_t j = 0; j < nj; ++j) {
      double* out = joints + (i * nj + j) * 6;
      joint_reaction(s_, static_cast<int>(j), yi, t[i], li, out, out + 3);
    }
  }
}

}  // namespace rancf
