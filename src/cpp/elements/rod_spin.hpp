// rod_spin.hpp -- the spin pieces of the rod's rotary inertia
// (docs/derivations/rod-kernel.md 11.2-11.3): the spin of a node's smallest rotation from its
// reference tangent and that of the smallest rotation between two tangents, each linear in the
// velocities (c . xdot), with their gradients, evaluated with a value-and-time-derivative number
// (Dual). Part of the rod kernel (rod_inertia.hpp includes it).
#ifndef RANCF_ROD_SPIN_HPP
#define RANCF_ROD_SPIN_HPP

#include <cmath>

namespace rancf::rod::detail {

// A value and its time derivative (forward mode along the motion).
struct Dual {
  double v = 0.0, d = 0.0;
  Dual() = default;
  Dual(double x, double dx = 0.0) : v(x), d(dx) {}  // NOLINT: implicit from double on purpose
};
inline Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
inline Dual operator*(double s, Dual a) { return {s * a.v, s * a.d}; }
inline Dual operator*(Dual a, double s) { return {s * a.v, s * a.d}; }
inline Dual operator/(double s, Dual a) {
  const double r = 1.0 / a.v;
  return {s * r, -s * r * r * a.d};
}
inline Dual sqrt(Dual a) {
  const double r = std::sqrt(a.v);
  return {r, 0.5 * a.d / r};
}
inline double val(double x) { return x; }
inline double val(Dual x) { return x.v; }

// Node spin (11.3): nu = c . w (w = xdot) with c = (x x tr) / E, E = |x| (|x| + tr . x); its
// gradient h = dnu/dx = (tr x w - q nu) / E, q = dE/dx = 2 x + (tr . x) x / |x| + |x| tr; and, if
// Dc, dc/dx = -([tr x] + c q^T) / E (values). Returns the alignment 1 + tr . t.
template <class T>
inline double node_spin(const T* x, const T* w, const double* tr, T* c, T& nu, T* h,
                        double (*Dc)[3]) {
  using std::sqrt;
  const T s = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  const T tx = tr[0] * x[0] + tr[1] * x[1] + tr[2] * x[2];
  const T iE = 1.0 / (s * (s + tx));
  c[0] = (x[1] * tr[2] - x[2] * tr[1]) * iE;
  c[1] = (x[2] * tr[0] - x[0] * tr[2]) * iE;
  c[2] = (x[0] * tr[1] - x[1] * tr[0]) * iE;
  nu = c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
  const double align = 1.0 + val(tx) / val(s);
  if (h == nullptr) return align;
  const T txs = tx * (1.0 / s);
  T q[3];
  for (int j = 0; j < 3; ++j) q[j] = 2.0 * x[j] + txs * x[j] + s * tr[j];
  h[0] = (tr[1] * w[2] - tr[2] * w[1] - q[0] * nu) * iE;
  h[1] = (tr[2] * w[0] - tr[0] * w[2] - q[1] * nu) * iE;
  h[2] = (tr[0] * w[1] - tr[1] * w[0] - q[2] * nu) * iE;
  if (Dc == nullptr) return align;
  const double trx[3][3] = {{0.0, -tr[2], tr[1]}, {tr[2], 0.0, -tr[0]}, {-tr[1], tr[0], 0.0}};
  const double ie = val(iE);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Dc[i][j] = -(trx[i][j] + val(c[i]) * val(q[j])) * ie;
  return align;
}

// Pair spin (11.3): sigma = c1 . w1 + c2 . w2 with k = x2 x x1, D = |x1||x2| + x1 . x2,
// ci = k / (|xi| D); its gradient (h on x1, x2), with y = w1/(s1 D) + w2/(s2 D) and
// sigma_i = ci . wi,
//   h1 = y x x2 - u1 sigma_1 - e1 sigma_2,   h2 = x1 x y - e2 sigma_1 - u2 sigma_2,
//   e1 = (s2 t1 + x2)/D, e2 = (s1 t2 + x1)/D, u1 = t1/s1 + e1, u2 = t2/s2 + e2;
// and, if Dc (6 x 6, rows c1, c2, columns x1, x2; values):
//   dc1/dx1 = [x2 x]/(s1 D) - c1 u1^T,  dc1/dx2 = -[x1 x]/(s1 D) - c1 e2^T
//   dc2/dx1 = [x2 x]/(s2 D) - c2 e1^T,  dc2/dx2 = -[x1 x]/(s2 D) - c2 u2^T.
// Returns the alignment 1 + t1 . t2.
template <class T>
inline double pair_spin(const T* x1, const T* x2, const T* w1, const T* w2, T* c, T& sig, T* h,
                        double (*Dc)[6]) {
  using std::sqrt;
  const T s1 = sqrt(x1[0] * x1[0] + x1[1] * x1[1] + x1[2] * x1[2]);
  const T s2 = sqrt(x2[0] * x2[0] + x2[1] * x2[1] + x2[2] * x2[2]);
  const T x12 = x1[0] * x2[0] + x1[1] * x2[1] + x1[2] * x2[2];
  const T s12 = s1 * s2, D = s12 + x12;
  const T iD = 1.0 / D, is1 = 1.0 / s1, is2 = 1.0 / s2;
  const T i1 = is1 * iD, i2 = is2 * iD;
  const T k[3] = {x2[1] * x1[2] - x2[2] * x1[1], x2[2] * x1[0] - x2[0] * x1[2],
                  x2[0] * x1[1] - x2[1] * x1[0]};
  for (int i = 0; i < 3; ++i) {
    c[i] = k[i] * i1;
    c[3 + i] = k[i] * i2;
  }
  const T sg1 = (k[0] * w1[0] + k[1] * w1[1] + k[2] * w1[2]) * i1;
  const T sg2 = (k[0] * w2[0] + k[1] * w2[1] + k[2] * w2[2]) * i2;
  sig = sg1 + sg2;
  const double align = 1.0 + val(x12) / val(s12);
  if (h == nullptr) return align;
  T e1[3], e2[3], u1[3], u2[3], y[3];
  const T r1 = s2 * is1 * iD, r2 = s1 * is2 * iD, q1 = is1 * is1, q2 = is2 * is2;
  for (int j = 0; j < 3; ++j) {
    e1[j] = r1 * x1[j] + x2[j] * iD;
    e2[j] = r2 * x2[j] + x1[j] * iD;
    u1[j] = x1[j] * q1 + e1[j];
    u2[j] = x2[j] * q2 + e2[j];
    y[j] = w1[j] * i1 + w2[j] * i2;
  }
  h[0] = y[1] * x2[2] - y[2] * x2[1] - u1[0] * sg1 - e1[0] * sg2;
  h[1] = y[2] * x2[0] - y[0] * x2[2] - u1[1] * sg1 - e1[1] * sg2;
  h[2] = y[0] * x2[1] - y[1] * x2[0] - u1[2] * sg1 - e1[2] * sg2;
  h[3] = x1[1] * y[2] - x1[2] * y[1] - e2[0] * sg1 - u2[0] * sg2;
  h[4] = x1[2] * y[0] - x1[0] * y[2] - e2[1] * sg1 - u2[1] * sg2;
  h[5] = x1[0] * y[1] - x1[1] * y[0] - e2[2] * sg1 - u2[2] * sg2;
  if (Dc == nullptr) return align;
  const double a1 = val(i1), a2 = val(i2);
  const double X2[3][3] = {{0.0, -val(x2[2]), val(x2[1])},
                           {val(x2[2]), 0.0, -val(x2[0])},
                           {-val(x2[1]), val(x2[0]), 0.0}};
  const double X1[3][3] = {{0.0, -val(x1[2]), val(x1[1])},
                           {val(x1[2]), 0.0, -val(x1[0])},
                           {-val(x1[1]), val(x1[0]), 0.0}};
  for (int i = 0; i < 3; ++i) {
    const double ca = val(c[i]), cb = val(c[3 + i]);
    for (int j = 0; j < 3; ++j) {
      Dc[i][j] = X2[i][j] * a1 - ca * val(u1[j]);
      Dc[i][3 + j] = -X1[i][j] * a1 - ca * val(e2[j]);
      Dc[3 + i][j] = X2[i][j] * a2 - cb * val(e1[j]);
      Dc[3 + i][3 + j] = -X1[i][j] * a2 - cb * val(u2[j]);
    }
  }
  return align;
}

}  // namespace rancf::rod::detail

#endif  // RANCF_ROD_SPIN_HPP
