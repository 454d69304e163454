// rod_moments.hpp -- point moments at a rod node: the generalized force and, by forward-mode
// derivatives with respect to r_x, its exact load stiffness (docs/derivations/rod-kernel.md section
// 6). Part of the rod kernel (rod_kernel.hpp).
#ifndef RANCF_ROD_MOMENTS_HPP
#define RANCF_ROD_MOMENTS_HPP

#include <cmath>

namespace rancf::rod {

namespace detail {

// A value with its derivatives with respect to the three components of r_x (forward mode);
// used only for the load stiffness of point moments (docs/derivations/rod-kernel.md 6).
struct D3 {
  double v = 0.0;
  double d[3] = {0.0, 0.0, 0.0};
};
inline D3 operator+(const D3& a, const D3& b) {
  return {a.v + b.v, {a.d[0] + b.d[0], a.d[1] + b.d[1], a.d[2] + b.d[2]}};
}
inline D3 operator-(const D3& a, const D3& b) {
  return {a.v - b.v, {a.d[0] - b.d[0], a.d[1] - b.d[1], a.d[2] - b.d[2]}};
}
inline D3 operator*(const D3& a, const D3& b) {
  D3 r{a.v * b.v, {}};
  for (int i = 0; i < 3; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
  return r;
}
inline D3 operator*(double s, const D3& a) {
  return {s * a.v, {s * a.d[0], s * a.d[1], s * a.d[2]}};
}
inline D3 operator/(const D3& a, const D3& b) {
  D3 r{a.v / b.v, {}};
  for (int i = 0; i < 3; ++i) r.d[i] = (a.d[i] - r.v * b.d[i]) / b.v;
  return r;
}
inline D3 sqrt(const D3& a) {
  D3 r{std::sqrt(a.v), {}};
  for (int i = 0; i < 3; ++i) r.d[i] = a.d[i] / (2.0 * r.v);
  return r;
}
inline double value(double x) { return x; }
inline double value(const D3& x) { return x.v; }
inline double lift(double x, double) { return x; }
inline D3 lift(double x, const D3&) { return {x, {0.0, 0.0, 0.0}}; }

// Generalized force of a moment m at a node with gradient rx and reference triad (tr, mr):
// virtual work m . dtheta with dtheta = t x dt + t (dphi + w . dt), the spin of the nodal triad
// about t including that of the smallest rotation, w . dt = du . v (docs/derivations/rod-kernel.md
// 6):
//   w = -(tr.v)/(1+c) mr + (t.mr)(tr.v)/(1+c)^2 tr - (t.mr)/(1+c) v,  c = tr.t,
//   g_rx = P [(m x t) + (m.t) w] / |rx|,  g_phi = m.t,  P = I - t t^T.
template <class T>
void moment_force(const double* m, const double* tr, const double* mr, const T* rx, T* g) {
  using std::sqrt;
  const T one = lift(1.0, rx[0]);
  const T n = sqrt(rx[0] * rx[0] + rx[1] * rx[1] + rx[2] * rx[2]);
  const T t[3] = {rx[0] / n, rx[1] / n, rx[2] / n};
  const T c = tr[0] * t[0] + tr[1] * t[1] + tr[2] * t[2];
  const T tm = mr[0] * t[0] + mr[1] * t[1] + mr[2] * t[2];
  const T k = tm / (one + c);
  T u[3], v[3], w[3], f[3];
  for (int i = 0; i < 3; ++i) u[i] = lift(mr[i], rx[0]) - k * (t[i] + lift(tr[i], rx[0]));
  v[0] = t[1] * u[2] - t[2] * u[1];
  v[1] = t[2] * u[0] - t[0] * u[2];
  v[2] = t[0] * u[1] - t[1] * u[0];
  const T tv = tr[0] * v[0] + tr[1] * v[1] + tr[2] * v[2];
  const T a = tv / (one + c);
  for (int i = 0; i < 3; ++i)
    w[i] = (k * a) * lift(tr[i], rx[0]) - a * lift(mr[i], rx[0]) - k * v[i];
  const T mt = m[0] * t[0] + m[1] * t[1] + m[2] * t[2];
  f[0] = m[1] * t[2] - m[2] * t[1] + mt * w[0];
  f[1] = m[2] * t[0] - m[0] * t[2] + mt * w[1];
  f[2] = m[0] * t[1] - m[1] * t[0] + mt * w[2];
  const T ft = f[0] * t[0] + f[1] * t[1] + f[2] * t[2];
  for (int i = 0; i < 3; ++i) g[i] = (f[i] - ft * t[i]) / n;
  g[3] = mt;
}

}  // namespace detail

// Point moment M at a node with gradient rx and reference triad (tref, m1ref):
// g[4] = generalized force on (r_x, phi) and, if kl, kl[4*4] = dg/d(rx, phi) (exact, forward mode;
// g does not depend on phi).  At a re-referenced node (tref = t) g = ((M x t)/|rx|, M.t).
inline void moment_load(const double* m, const double* tref, const double* m1ref, const double* rx,
                        double* g, double* kl) {
  if (!kl) {
    detail::moment_force(m, tref, m1ref, rx, g);
    return;
  }
  detail::D3 x[3], gd[4];
  for (int i = 0; i < 3; ++i) {
    x[i].v = rx[i];
    x[i].d[i] = 1.0;
  }
  detail::moment_force(m, tref, m1ref, x, gd);
  for (int i = 0; i < 4; ++i) {
    g[i] = gd[i].v;
    for (int j = 0; j < 3; ++j) kl[4 * i + j] = gd[i].d[j];
    kl[4 * i + 3] = 0.0;
  }
}

}  // namespace rancf::rod

#endif  // RANCF_ROD_MOMENTS_HPP
