#include "assembly.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "registry.hpp"

namespace rancf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Gradient blocks of clamped nodes: e <- T e (to q) for the element's two nodes.
void rotate_to_q(const Model& m, int el, double* e) {
  const int d = m.dim;
  for (int a = 0; a < 2; ++a) {
    const std::int64_t r = m.supports.rot_of_node[el + a];
    if (r < 0) continue;
    const double* bas = m.supports.rot + r * d * d;
    double* g = e + a * m.dpn + d;
    double tmp[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) tmp[i] += bas[i * d + j] * g[j];
    for (int i = 0; i < d; ++i) g[i] = tmp[i];
  }
}

// f <- T^T f and K <- T^T K T for the element's clamped nodes.
void rotate_back(const Model& m, int el, double* fe, double* ke) {
  const int d = m.dim, nde = m.nde();
  for (int a = 0; a < 2; ++a) {
    const std::int64_t r = m.supports.rot_of_node[el + a];
    if (r < 0) continue;
    const double* bas = m.supports.rot + r * d * d;
    const int o = a * m.dpn + d;
    double tmp[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) tmp[i] += bas[j * d + i] * fe[o + j];
    for (int i = 0; i < d; ++i) fe[o + i] = tmp[i];
    if (ke == nullptr) continue;
    for (int c = 0; c < nde; ++c) {  // rows
      double t[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j) t[i] += bas[j * d + i] * ke[(o + j) * nde + c];
      for (int i = 0; i < d; ++i) ke[(o + i) * nde + c] = t[i];
    }
    for (int c = 0; c < nde; ++c) {  // columns
      double t[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j) t[i] += ke[c * nde + o + j] * bas[j * d + i];
      for (int i = 0; i < d; ++i) ke[c * nde + o + i] = t[i];
    }
  }
}

bool has_rotation(const Model& m, int el) {
  return m.supports.rot_of_node[el] >= 0 || m.supports.rot_of_node[el + 1] >= 0;
}

}  // namespace

void assemble(const Model& m, const double* y, double* f, const BandView* k, double k_scale) {
  const ElementKernel& kern = kernel_for(m);
  const int nde = m.nde(), n = m.n();
  std::fill(f, f + n, 0.0);
  std::array<double, kMaxElementDofs> e{}, fe{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
  double* kep = k != nullptr ? ke.data() : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    const int base = el * m.dpn;
    std::copy(y + base, y + base + nde, e.begin());
    const bool rotated = has_rotation(m, el);
    if (rotated) rotate_to_q(m, el, e.data());
    kern.forces(m, el, e.data(), fe.data(), kep);
    if (rotated) rotate_back(m, el, fe.data(), kep);
    for (int i = 0; i < nde; ++i) f[base + i] += fe[static_cast<std::size_t>(i)];
    if (k == nullptr) continue;
    for (int j = 0; j < nde; ++j) {
      double* colj = &k->at(base, base + j);  // A(base + i, base + j) = colj[(i) * rs]
      for (int i = 0; i < nde; ++i) colj[i * k->rs] += k_scale * kep[i * nde + j];
    }
  }
}

double strain_energy(const Model& m, const double* y) {
  const ElementKernel& kern = kernel_for(m);
  const int nde = m.nde();
  std::array<double, kMaxElementDofs> e{};
  double total = 0.0;
  for (int el = 0; el < m.n_el; ++el) {
    const int base = el * m.dpn;
    std::copy(y + base, y + base + nde, e.begin());
    if (has_rotation(m, el)) rotate_to_q(m, el, e.data());
    total += kern.energy(m, el, e.data());
  }
  return total;
}

void external_force(const Model& m, double t, double* f) {
  const int n = m.n();
  std::copy(m.loads.f_gravity, m.loads.f_gravity + n, f);
  for (int p = 0; p < m.loads.n_point; ++p) {
    double fac = 1.0;
    if (m.loads.freq[p] > 0.0) fac = std::sin(2.0 * kPi * m.loads.freq[p] * t);
    for (int i = 0; i < m.dim; ++i) f[m.loads.base[p] + i] += m.loads.f0[p * m.dim + i] * fac;
  }
}

}  // namespace rancf
