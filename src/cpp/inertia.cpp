#include "inertia.hpp"

#include <algorithm>
#include <array>

#include "assembly.hpp"
#include "rod.hpp"

namespace rancf {

namespace {

// Element coordinates of el from a global vector in model coordinates, to q (zeros if x null).
void gather(const Model& m, int el, const double* x, double* e) {
  const int nde = m.nde(), base = el * m.dpn;
  if (x == nullptr) {
    std::fill(e, e + nde, 0.0);
    return;
  }
  std::copy(x + base, x + base + nde, e);
  if (has_rotation(m, el)) rotate_to_q(m, el, e);
}

}  // namespace

bool has_rotary_inertia(const Model& m) {
  return m.kind == ElementKind::rod && (m.rotary.polar > 0.0 || m.rotary.bend > 0.0);
}

void assemble_inertia(const Model& m, const double* y, const double* v, const double* a,
                      const InertiaTerms& terms, double* r, const BandView* jac) {
  if (!has_rotary_inertia(m)) return;
  const int nde = m.nde();
  std::array<double, kMaxElementDofs> e{}, ed{}, edd{}, fe{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
  double* kep = jac != nullptr ? ke.data() : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    const int base = el * m.dpn;
    gather(m, el, y, e.data());
    gather(m, el, v, ed.data());
    gather(m, el, a, edd.data());
    rod_inertia(m, el, e.data(), ed.data(), edd.data(), terms.damping, terms.ck, terms.cv, terms.ca,
                fe.data(), kep);
    if (has_rotation(m, el)) rotate_back(m, el, fe.data(), kep);
    for (int i = 0; i < nde; ++i) r[base + i] += fe[static_cast<std::size_t>(i)];
    if (jac == nullptr) continue;
    for (int j = 0; j < nde; ++j) {
      double* colj = &jac->at(base, base + j);
      for (int i = 0; i < nde; ++i) colj[i * jac->rs] += kep[i * nde + j];
    }
  }
}

double rotary_kinetic_energy(const Model& m, const double* y, const double* v, bool current) {
  if (!has_rotary_inertia(m)) return 0.0;
  std::array<double, kMaxElementDofs> e{}, ed{};
  double total = 0.0;
  for (int el = 0; el < m.n_el; ++el) {
    gather(m, el, y, e.data());
    gather(m, el, v, ed.data());
    total += rod_rotary_energy(m, el, e.data(), ed.data(), current);
  }
  return total;
}

void rotary_angular_momentum(const Model& m, const double* y, const double* v, bool current,
                             double* out) {
  std::fill(out, out + 3, 0.0);
  if (!has_rotary_inertia(m)) return;
  std::array<double, kMaxElementDofs> e{}, ed{};
  for (int el = 0; el < m.n_el; ++el) {
    gather(m, el, y, e.data());
    gather(m, el, v, ed.data());
    rod_rotary_momentum(m, el, e.data(), ed.data(), current, out);
  }
}

void rereference_rates(const Model& m, const double* y, double* v, double* a) {
  if (m.kind != ElementKind::rod) return;
  for (int node = 0; node < m.n_nodes; ++node) {
    const int o = node * m.dpn + 6;  // the twist
    if (m.supports.fixed[o] != 0) continue;
    double rx[3], rxd[3], rxdd[3];
    nodal_gradient(m, y, node, rx);
    nodal_gradient(m, v, node, rxd);
    nodal_gradient(m, a, node, rxdd);
    rod_rereference_rates(m, node, rx, rxd, rxdd, v[o], a[o]);
  }
}

}  // namespace rancf
