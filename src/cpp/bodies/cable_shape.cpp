#include "bodies/cable_shape.hpp"

namespace rancf {

void cable_shape(const double* w, double l, double xi, double* n0, double* n1, double* n2) {
  // Bernstein basis B_i, the rational R_i = w_i B_i / D and their derivatives
  const double u = 1.0 - xi;
  const double b0[4] = {u * u * u, 3.0 * xi * u * u, 3.0 * xi * xi * u, xi * xi * xi};
  const double b1[4] = {-3.0 * u * u, 3.0 * u * u - 6.0 * xi * u, 6.0 * xi * u - 3.0 * xi * xi,
                        3.0 * xi * xi};
  const double b2[4] = {6.0 * u, 6.0 * xi - 12.0 * u, 6.0 * u - 12.0 * xi, 6.0 * xi};
  double d0 = 0.0, d1 = 0.0, d2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    d0 += w[i] * b0[i];
    d1 += w[i] * b1[i];
    d2 += w[i] * b2[i];
  }
  double r0[4], r1[4], r2[4];
  const double inv = 1.0 / d0;
  for (int i = 0; i < 4; ++i) {
    r0[i] = w[i] * b0[i] * inv;
    r1[i] = (w[i] * b1[i] - r0[i] * d1) * inv;
    r2[i] = (w[i] * b2[i] - 2.0 * r1[i] * d1 - r0[i] * d2) * inv;
  }
  const double c1 = l * w[0] / (3.0 * w[1]), c3 = -l * w[3] / (3.0 * w[2]);
  const double* rr[3] = {r0, r1, r2};
  double* out[3] = {n0, n1, n2};
  for (int k = 0; k < 3; ++k) {
    if (out[k] == nullptr) continue;
    const double* r = rr[k];
    out[k][0] = r[0] + r[1];
    out[k][1] = c1 * r[1];
    out[k][2] = r[2] + r[3];
    out[k][3] = c3 * r[2];
  }
}

}  // namespace rancf
