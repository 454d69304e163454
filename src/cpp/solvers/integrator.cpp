#include "solvers/integrator.hpp"

#include <vector>

#include "bodies/inertia.hpp"

namespace rancf {

namespace {
std::size_t sz(int n) { return static_cast<std::size_t>(n); }
}  // namespace

double kinetic_energy(const Model& m, const double* y, const double* v) {
  return kinetic_energy(m, v) + rotary_kinetic_energy(m, y, v);
}

double kinetic_energy(const Model& m, const double* v) {
  const int n = m.n();
  std::vector<double> mv(sz(n));
  band_matvec(m.mass_band, v, n, m.ku(), mv.data());
  double k = 0.0;
  for (int i = 0; i < n; ++i) k += 0.5 * v[i] * mv[sz(i)];
  return k;
}

double gravity_energy(const Model& m, const double* y) {
  double g = 0.0;
  for (int i = 0; i < m.n(); ++i) g -= m.loads.f_gravity[i] * (y[i] - m.y_ref[i]);
  return g;
}

}  // namespace rancf
