#include "system/rigid.hpp"

#include "system/places.hpp"

namespace rancf {

namespace {

// G(p): 3 x 4, body angular velocity w = 2 G(p) p'.
void g_matrix(const double* p, double (*G)[4]) {
  const double g[3][4] = {
      {-p[1], p[0], p[3], -p[2]}, {-p[2], -p[3], p[0], p[1]}, {-p[3], p[2], -p[1], p[0]}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) G[i][j] = g[i][j];
}

// y = G(p) x (3), and z = G(p)^T u (4)
void g_times(const double* p, const double* x, double* y) {
  double G[3][4];
  g_matrix(p, G);
  for (int i = 0; i < 3; ++i)
    y[i] = G[i][0] * x[0] + G[i][1] * x[1] + G[i][2] * x[2] + G[i][3] * x[3];
}
void gt_times(const double* p, const double* u, double* z) {
  double G[3][4];
  g_matrix(p, G);
  for (int j = 0; j < 4; ++j) z[j] = G[0][j] * u[0] + G[1][j] * u[1] + G[2][j] * u[2];
}

double kappa(const RigidInertia& b) {
  const double* J = b.inertia;
  double m = J[0];
  if (J[1] > m) m = J[1];
  if (J[2] > m) m = J[2];
  return 4.0 * m;
}

}  // namespace

int rigid_size(const RigidInertia& b) {
  if (b.point_mass) return b.dim;
  return b.dim == 2 ? 3 : 7;
}

void rigid_inertial_force(const RigidInertia& b, const double* q, const double* v, const double* a,
                          double ck, double cv, double ca, double* f, double* k) {
  const int n = rigid_size(b);
  if (k != nullptr)
    for (int i = 0; i < n * n; ++i) k[i] = 0.0;
  const int nt = b.point_mass ? b.dim : (b.dim == 2 ? 2 : 3);  // translational coordinates
  for (int i = 0; i < nt; ++i) {
    f[i] = b.mass * a[i];
    if (k != nullptr) k[i * n + i] = ca * b.mass;
  }
  if (b.point_mass) return;
  if (b.dim == 2) {
    f[2] = b.inertia[0] * a[2];
    if (k != nullptr) k[8] = ca * b.inertia[0];
    return;
  }
  const double* p = q + 3;
  const double* pd = v + 3;
  const double* pdd = a + 3;
  const double* J = b.inertia;
  const double kap = kappa(b);
  double w[3], wd[3], jw[3], jwd[3];
  g_times(p, pdd, w);  // G(p) p''
  g_times(p, pd, wd);  // G(p) p'
  for (int i = 0; i < 3; ++i) {
    jw[i] = J[i] * w[i];
    jwd[i] = J[i] * wd[i];
  }
  double t1[4], t2[4];
  gt_times(p, jw, t1);    // G^T J G p''
  gt_times(pd, jwd, t2);  // G(p')^T J G(p) p'
  double pa = 0.0;
  for (int i = 0; i < 4; ++i) pa += p[i] * pdd[i];
  for (int i = 0; i < 4; ++i) f[3 + i] = 4.0 * t1[i] + 8.0 * t2[i] + kap * p[i] * pa;
  if (k == nullptr) return;
  for (int j = 0; j < 4; ++j) {
    double e[4] = {0.0, 0.0, 0.0, 0.0};
    e[j] = 1.0;
    double ge[3], gie_pdd[3], gie_pd[3];
    g_times(e, pdd, gie_pdd);  // G_j p''
    g_times(e, pd, gie_pd);    // G_j p'
    g_times(p, e, ge);         // G(p) e_j
    // dF/dp_j = 4 [G_j^T J G p'' + G^T J G_j p''] + 8 G(p')^T J G_j p' + kap (e_j pa + p p''_j)
    double a1[3], a2[3], a3[3], u1[4], u2[4], u3[4];
    for (int i = 0; i < 3; ++i) {
      a1[i] = J[i] * w[i];
      a2[i] = J[i] * gie_pdd[i];
      a3[i] = J[i] * gie_pd[i];
    }
    gt_times(e, a1, u1);
    gt_times(p, a2, u2);
    gt_times(pd, a3, u3);
    // dF/dp'_j = 8 [G_j^T J G p' + G(p')^T J G(p) e_j]
    double b1[3], b2[3], v1[4], v2[4];
    for (int i = 0; i < 3; ++i) {
      b1[i] = J[i] * wd[i];
      b2[i] = J[i] * ge[i];
    }
    gt_times(e, b1, v1);
    gt_times(pd, b2, v2);
    // dF/dp''_j = 4 G^T J G e_j + kap p p_j
    double c1[4];
    gt_times(p, b2, c1);
    for (int i = 0; i < 4; ++i) {
      const double dq =
          4.0 * (u1[i] + u2[i]) + 8.0 * u3[i] + kap * ((i == j ? pa : 0.0) + p[i] * pdd[j]);
      const double dv = 8.0 * (v1[i] + v2[i]);
      const double da = 4.0 * c1[i] + kap * p[i] * p[j];
      k[(3 + i) * n + 3 + j] = ck * dq + cv * dv + ca * da;
    }
  }
}

double rigid_kinetic_energy(const RigidInertia& b, const double* q, const double* v) {
  const int nt = b.point_mass ? b.dim : (b.dim == 2 ? 2 : 3);
  double t = 0.0;
  for (int i = 0; i < nt; ++i) t += 0.5 * b.mass * v[i] * v[i];
  if (b.point_mass) return t;
  if (b.dim == 2) return t + 0.5 * b.inertia[0] * v[2] * v[2];
  double w[3];
  g_times(q + 3, v + 3, w);
  for (int i = 0; i < 3; ++i) t += 0.5 * b.inertia[i] * 4.0 * w[i] * w[i];
  return t;
}

void rigid_angular_momentum(const RigidInertia& b, const double* q, const double* v, double* out) {
  out[0] = out[1] = out[2] = 0.0;
  if (b.dim == 2) {
    out[2] = b.mass * (q[0] * v[1] - q[1] * v[0]);
    if (!b.point_mass) out[2] += b.inertia[0] * v[2];
    return;
  }
  const double m = b.mass;
  out[0] = m * (q[1] * v[2] - q[2] * v[1]);
  out[1] = m * (q[2] * v[0] - q[0] * v[2]);
  out[2] = m * (q[0] * v[1] - q[1] * v[0]);
  if (b.point_mass) return;
  double w[3], R[9];
  g_times(q + 3, v + 3, w);
  quaternion_rotation(q + 3, R, nullptr);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i] += R[3 * i + j] * b.inertia[j] * 2.0 * w[j];
}

}  // namespace rancf
