#include "system/places.hpp"

#include <cmath>

#include "elements/rod_frames.hpp"

namespace rancf {

int place_size(PlaceKind kind, int dim) {
  switch (kind) {
    case PlaceKind::ground:
      return 0;
    case PlaceKind::cable:
      return 2 * dim;
    case PlaceKind::rod:
      return 7;
    case PlaceKind::beam:
    case PlaceKind::rigid2d:
      return 3;
    case PlaceKind::rigid3d:
      return 7;
    case PlaceKind::mass:
      return dim;
  }
  return 0;
}

void rotation_matrix(int dim, const double* rot, double* R) {
  for (int i = 0; i < 9; ++i) R[i] = i % 4 == 0 ? 1.0 : 0.0;
  if (dim == 2) {
    const double c = std::cos(rot[0]), s = std::sin(rot[0]);
    R[0] = c, R[1] = -s, R[3] = s, R[4] = c;
    return;
  }
  const double a = std::sqrt(rot[0] * rot[0] + rot[1] * rot[1] + rot[2] * rot[2]);
  if (a == 0.0) return;
  const double k[3] = {rot[0] / a, rot[1] / a, rot[2] / a};
  const double s = std::sin(a), c1 = 1.0 - std::cos(a);
  const double K[9] = {0.0, -k[2], k[1], k[2], 0.0, -k[0], -k[1], k[0], 0.0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double kk = k[i] * k[j] - (i == j ? 1.0 : 0.0);  // (K^2)_ij
      R[3 * i + j] += s * K[3 * i + j] + c1 * kk;
    }
}

void quaternion_rotation(const double* p, double* R, double (*dR)[9]) {
  // R = (p0^2 - v.v) I + 2 v v^T + 2 p0 [v]x,  v = (p1, p2, p3)
  const double p0 = p[0], a = p[1], b = p[2], c = p[3];
  const double s = p0 * p0 - a * a - b * b - c * c;
  const double r[9] = {s + 2 * a * a,        2 * (a * b - p0 * c), 2 * (a * c + p0 * b),
                       2 * (a * b + p0 * c), s + 2 * b * b,        2 * (b * c - p0 * a),
                       2 * (a * c - p0 * b), 2 * (b * c + p0 * a), s + 2 * c * c};
  for (int i = 0; i < 9; ++i) R[i] = r[i];
  if (dR == nullptr) return;
  const double d0[9] = {2 * p0, -2 * c, 2 * b, 2 * c, 2 * p0, -2 * a, -2 * b, 2 * a, 2 * p0};
  const double d1[9] = {2 * a, 2 * b, 2 * c, 2 * b, -2 * a, -2 * p0, 2 * c, 2 * p0, -2 * a};
  const double d2[9] = {-2 * b, 2 * a, 2 * p0, 2 * a, 2 * b, 2 * c, -2 * p0, 2 * c, -2 * b};
  const double d3[9] = {-2 * c, -2 * p0, 2 * a, 2 * p0, -2 * c, 2 * b, 2 * a, 2 * b, 2 * c};
  for (int i = 0; i < 9; ++i) {
    dR[0][i] = d0[i];
    dR[1][i] = d1[i];
    dR[2][i] = d2[i];
    dR[3][i] = d3[i];
  }
}

namespace {

void planar_frame(double psi, int j, PlaceEval& o) {
  // f0 = (cos, sin), f1 = (-sin, cos), f2 = e_z; derivatives with respect to local j (= psi)
  const double c = std::cos(psi), s = std::sin(psi);
  o.nf = 3;
  o.f[0][0] = c, o.f[0][1] = s;
  o.f[1][0] = -s, o.f[1][1] = c;
  o.f[2][2] = 1.0;
  o.df[0][0][j] = -s, o.df[0][1][j] = c;
  o.df[1][0][j] = -c, o.df[1][1][j] = -s;
}

}  // namespace

void eval_place(const PlaceInfo& info, const double* q, PlaceEval& o) {
  const int d = info.dim;
  o.n = place_size(info.kind, d);
  o.nf = 0;
  // zero where the cases below leave entries unset: the first 8 columns (o.n <= 7), a fixed
  // count the compiler writes out (a call to memset for each row cost more than the rest)
  static_assert(kMaxLocal >= 8);
  const bool translates = info.kind == PlaceKind::mass || info.kind == PlaceKind::cable ||
                          info.kind == PlaceKind::rod || info.kind == PlaceKind::beam;
  if (!info.frames && (translates || info.kind == PlaceKind::ground)) {
    for (int i = 0; i < 3; ++i) {  // the position: the node's (its first coordinates)
      o.x[i] = info.kind == PlaceKind::ground ? info.point[i] : 0.0;
      for (int j = 0; j < 8; ++j) o.dx[i][j] = 0.0;
    }
    const int nx = info.kind == PlaceKind::ground ? 0 : info.kind == PlaceKind::rod ? 3 : d;
    for (int i = 0; i < nx; ++i) {
      o.x[i] = q[i];
      o.dx[i][i] = 1.0;
    }
    return;
  }
  for (int i = 0; i < 3; ++i) {
    o.x[i] = 0.0;
    for (int j = 0; j < 8; ++j) o.dx[i][j] = 0.0;
    for (int k = 0; k < 3; ++k) {
      o.f[k][i] = 0.0;
      for (int j = 0; j < 8; ++j) o.df[k][i][j] = 0.0;
    }
  }
  switch (info.kind) {
    case PlaceKind::ground:
      for (int i = 0; i < 3; ++i) o.x[i] = info.point[i];
      o.nf = 3;
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) o.f[k][i] = info.frame[3 * i + k];  // column k
      return;
    case PlaceKind::mass:
      for (int i = 0; i < d; ++i) {
        o.x[i] = q[i];
        o.dx[i][i] = 1.0;
      }
      return;
    case PlaceKind::cable: {
      for (int i = 0; i < d; ++i) {
        o.x[i] = q[i];
        o.dx[i][i] = 1.0;
      }
      const double* g = q + d;
      double s2 = 0.0;
      for (int i = 0; i < d; ++i) s2 += g[i] * g[i];
      const double s = std::sqrt(s2);
      double t[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < d; ++i) t[i] = g[i] / s;
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j) o.df[0][i][d + j] = ((i == j ? 1.0 : 0.0) - t[i] * t[j]) / s;
      for (int i = 0; i < 3; ++i) o.f[0][i] = t[i];
      if (d == 3) {
        o.nf = 1;
        return;
      }
      o.nf = 3;  // planar: n = e_z x t, e_z
      o.f[1][0] = -t[1], o.f[1][1] = t[0];
      o.f[2][2] = 1.0;
      for (int j = 0; j < 2; ++j) {
        o.df[1][0][2 + j] = -o.df[0][1][2 + j];
        o.df[1][1][2 + j] = o.df[0][0][2 + j];
      }
      return;
    }
    case PlaceKind::rod: {
      for (int i = 0; i < 3; ++i) {
        o.x[i] = q[i];
        o.dx[i][i] = 1.0;
      }
      rod::detail::FrameJet J;
      rod::detail::frame_jet<false>(info.tref, info.m1ref, q + 3, J);
      const double c = std::cos(q[6]), s = std::sin(q[6]);
      o.nf = 3;
      for (int i = 0; i < 3; ++i) {
        o.f[0][i] = J.t[i];
        o.f[1][i] = c * J.u[i] + s * J.v[i];
        o.f[2][i] = c * J.v[i] - s * J.u[i];
        for (int j = 0; j < 3; ++j) {
          o.df[0][i][3 + j] = J.dt[i][j];
          o.df[1][i][3 + j] = c * J.du[i][j] + s * J.dv[i][j];
          o.df[2][i][3 + j] = c * J.dv[i][j] - s * J.du[i][j];
        }
        o.df[1][i][6] = o.f[2][i];   // d m1 / d phi = m2
        o.df[2][i][6] = -o.f[1][i];  // d m2 / d phi = -m1
      }
      return;
    }
    case PlaceKind::beam:
      o.x[0] = q[0], o.x[1] = q[1];
      o.dx[0][0] = o.dx[1][1] = 1.0;
      planar_frame(q[2] + info.angle0, 2, o);
      return;
    case PlaceKind::rigid2d: {
      const double c = std::cos(q[2]), s = std::sin(q[2]);
      const double sx = info.point[0], sy = info.point[1];
      o.x[0] = q[0] + c * sx - s * sy;
      o.x[1] = q[1] + s * sx + c * sy;
      o.dx[0][0] = o.dx[1][1] = 1.0;
      o.dx[0][2] = -s * sx - c * sy;
      o.dx[1][2] = c * sx - s * sy;
      planar_frame(q[2], 2, o);
      return;
    }
    case PlaceKind::rigid3d: {
      double R[9], dR[4][9];
      quaternion_rotation(q + 3, R, dR);
      const double* sp = info.point;
      o.nf = 3;
      for (int i = 0; i < 3; ++i) {
        o.x[i] = q[i] + R[3 * i] * sp[0] + R[3 * i + 1] * sp[1] + R[3 * i + 2] * sp[2];
        o.dx[i][i] = 1.0;
        for (int j = 0; j < 4; ++j)
          o.dx[i][3 + j] =
              dR[j][3 * i] * sp[0] + dR[j][3 * i + 1] * sp[1] + dR[j][3 * i + 2] * sp[2];
        for (int k = 0; k < 3; ++k) {
          o.f[k][i] = R[3 * i + k];  // column k
          for (int j = 0; j < 4; ++j) o.df[k][i][3 + j] = dR[j][3 * i + k];
        }
      }
      return;
    }
  }
}

}  // namespace rancf
