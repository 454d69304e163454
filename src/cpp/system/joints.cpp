#include "system/joints.hpp"

#include <algorithm>
#include <cmath>

namespace rancf {

namespace {

constexpr int kW = 2 * kMaxLocal;

/// A world vector and its derivatives with respect to [A's locals, B's locals]: the first w
/// columns of d are set (a joint's places have a few of the 2 kMaxLocal; clearing all of them
/// at every evaluation was most of a joint's cost); w = 0: the value alone.
struct Vec {
  int w = 0;
  double v[3] = {0.0, 0.0, 0.0};
  double d[3][kW];
  Vec() = default;
  explicit Vec(int width) : w(width) {
    for (auto& row : d) {  // a fixed count the compiler writes out, for the common widths
      if (w <= 16) {
        for (int j = 0; j < 16; ++j) row[j] = 0.0;
      } else {
        std::fill(row, row + w, 0.0);
      }
    }
  }
};

Vec position(const PlaceEval& p, int off, int w) {
  Vec out(w);
  for (int i = 0; i < 3; ++i) {
    out.v[i] = p.x[i];
    for (int j = 0; j < (w > 0 ? p.n : 0); ++j) out.d[i][off + j] = p.dx[i][j];
  }
  return out;
}

Vec combo(const PlaceEval& p, int off, const double* c, int w) {
  Vec out(w);
  for (int k = 0; k < p.nf; ++k) {
    if (c[k] == 0.0) continue;
    for (int i = 0; i < 3; ++i) {
      out.v[i] += c[k] * p.f[k][i];
      for (int j = 0; j < (w > 0 ? p.n : 0); ++j) out.d[i][off + j] += c[k] * p.df[k][i][j];
    }
  }
  return out;
}

Vec frame(const PlaceEval& p, int off, int k, int w) {
  double c[3] = {0.0, 0.0, 0.0};
  c[k] = 1.0;
  return combo(p, off, c, w);
}

Vec sub(const Vec& a, const Vec& b) {
  Vec out(a.w);
  for (int i = 0; i < 3; ++i) {
    out.v[i] = a.v[i] - b.v[i];
    for (int j = 0; j < a.w; ++j) out.d[i][j] = a.d[i][j] - b.d[i][j];
  }
  return out;
}

/// a . b into g and its gradient into row (width w).
void dot(const Vec& a, const Vec& b, int w, double* g, double* row, double scale = 1.0) {
  *g += scale * (a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2]);
  for (int j = 0; j < w; ++j)
    row[j] += scale * (a.d[0][j] * b.v[0] + a.v[0] * b.d[0][j] + a.d[1][j] * b.v[1] +
                       a.v[1] * b.d[1][j] + a.d[2][j] * b.v[2] + a.v[2] * b.d[2][j]);
}

/// (a x b) . c into g and its gradient into row.
void triple(const Vec& a, const Vec& b, const Vec& c, int w, double* g, double* row, double scale) {
  auto cross = [](const double* x, const double* y, double* z) {
    z[0] = x[1] * y[2] - x[2] * y[1];
    z[1] = x[2] * y[0] - x[0] * y[2];
    z[2] = x[0] * y[1] - x[1] * y[0];
  };
  double ab[3];
  cross(a.v, b.v, ab);
  *g += scale * (ab[0] * c.v[0] + ab[1] * c.v[1] + ab[2] * c.v[2]);
  for (int j = 0; j < w; ++j) {
    const double da[3] = {a.d[0][j], a.d[1][j], a.d[2][j]};
    const double db[3] = {b.d[0][j], b.d[1][j], b.d[2][j]};
    double x1[3], x2[3];
    cross(da, b.v, x1);
    cross(a.v, db, x2);
    double s = 0.0;
    for (int i = 0; i < 3; ++i) s += (x1[i] + x2[i]) * c.v[i] + ab[i] * c.d[i][j];
    row[j] += scale * s;
  }
}

}  // namespace

int joint_rows(const JointInfo& j) {
  const int d = j.dim, drive = j.driven ? 1 : 0;
  switch (j.kind) {
    case JointKind::pin:
      return d + drive;
    case JointKind::fixed:
      return d == 2 ? 3 : 6;
    case JointKind::tangent:
      return 5;
    case JointKind::revolute:
      return (d == 2 ? 2 : 5) + drive;
    case JointKind::slider:
      return d - 1;
    case JointKind::sliding:
      return d + 1;
  }
  return 0;
}

void eval_joint(const JointInfo& j, const PlaceEval& a, const PlaceEval& b, double theta, double* g,
                double* jac) {
  const int rows = joint_rows(j), d = j.dim;
  double none[1];  // g alone: no columns (w = 0), the Jacobian's pointer unused
  const int w = jac != nullptr ? a.n + b.n : 0;
  if (jac == nullptr) jac = none;
  for (int r = 0; r < rows; ++r) {
    g[r] = 0.0;
    for (int c = 0; c < w; ++c) jac[r * w + c] = 0.0;
  }
  if (j.kind == JointKind::sliding) return;  // sliding.hpp
  int r = 0;
  const Vec xa = position(a, 0, w), xb = position(b, a.n, w);
  const Vec rel = sub(xa, xb);
  if (j.kind == JointKind::slider) {
    for (int i = 0; i < d - 1; ++i, ++r)
      dot(rel, combo(b, a.n, j.normals_b[i], w), w, g + r, jac + r * w);
    return;
  }
  for (int i = 0; i < d; ++i, ++r) {  // positions
    g[r] = rel.v[i];
    for (int c = 0; c < w; ++c) jac[r * w + c] = rel.d[i][c];
  }
  if (j.kind == JointKind::pin && !j.driven) return;  // the positions are all its rows
  const bool planar_angle =
      d == 2 && (j.kind == JointKind::fixed ||
                 ((j.kind == JointKind::pin || j.kind == JointKind::revolute) && j.driven));
  if (planar_angle) {  // sin(psi_A - psi_B - beta): s cos(beta) - c sin(beta)
    const double beta = j.beta0 + (j.kind == JointKind::fixed ? 0.0 : theta);
    const Vec fa = frame(a, 0, 0, w), fb0 = frame(b, a.n, 0, w), fb1 = frame(b, a.n, 1, w);
    dot(fa, fb1, w, g + r, jac + r * w, std::cos(beta));
    dot(fa, fb0, w, g + r, jac + r * w, -std::sin(beta));
    return;
  }
  if (d == 2) return;
  if (j.kind == JointKind::fixed) {
    Vec av[3], cv[3];
    for (int k = 0; k < 3; ++k) {
      av[k] = frame(a, 0, k, w);
      cv[k] = combo(b, a.n, j.rel[k], w);
    }
    for (int k = 0; k < 3; ++k, ++r) dot(av[k], cv[(k + 1) % 3], w, g + r, jac + r * w);
    return;
  }
  const Vec e = j.kind == JointKind::tangent ? frame(a, 0, 0, w) : combo(a, 0, j.axis_a, w);
  for (int i = 0; i < 2; ++i, ++r) dot(e, combo(b, a.n, j.normals_b[i], w), w, g + r, jac + r * w);
  if (j.kind == JointKind::revolute && j.driven) {  // sin(angle - beta) about e_A
    const double beta = j.beta0 + theta;
    const Vec wa = combo(a, 0, j.w_a, w), wb = combo(b, a.n, j.w_b, w);
    triple(wb, wa, e, w, g + r, jac + r * w, std::cos(beta));  // sin(angle)
    dot(wa, wb, w, g + r, jac + r * w, -std::sin(beta));       // cos(angle)
  }
}

}  // namespace rancf
