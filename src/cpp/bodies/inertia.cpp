#include "bodies/inertia.hpp"

#include <algorithm>
#include <array>

#include "bodies/assembly.hpp"
#include "elements/registry.hpp"
#include "elements/rod.hpp"

namespace rancf {

bool has_rotary_inertia(const Model& m) {
  return kernel_for(m).triads && (m.rotary.polar > 0.0 || m.rotary.bend > 0.0);
}

void assemble_inertia(const Model& m, const double* y, const double* v, const double* a,
                      const InertiaTerms& terms, double* r, const BandView* jac) {
  if (!has_rotary_inertia(m)) return;
  std::array<double, kMaxElementDofs> e{}, ed{}, edd{}, fe{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
  double* kep = jac != nullptr ? ke.data() : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    gather_element(m, el, y, e.data());
    gather_element(m, el, v, ed.data());
    gather_element(m, el, a, edd.data());
    rod_inertia(m, el, e.data(), ed.data(), edd.data(), terms.damping, terms.ck, terms.cv, terms.ca,
                fe.data(), kep);
    scatter_element(m, el, fe.data(), kep, r, jac, 1.0);
  }
}

double rotary_kinetic_energy(const Model& m, const double* y, const double* v, bool current) {
  if (!has_rotary_inertia(m)) return 0.0;
  std::array<double, kMaxElementDofs> e{}, ed{};
  double total = 0.0;
  for (int el = 0; el < m.n_el; ++el) {
    gather_element(m, el, y, e.data());
    gather_element(m, el, v, ed.data());
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
    gather_element(m, el, y, e.data());
    gather_element(m, el, v, ed.data());
    rod_rotary_momentum(m, el, e.data(), ed.data(), current, out);
  }
}

void rereference_rates(const Model& m, const double* y, double* v, double* a) {
  if (!kernel_for(m).triads) return;
  for (int node = 0; node < m.n_nodes; ++node) {
    const int o = twist_index(m, node);
    if (m.supports.fixed[o] != 0) continue;
    double rx[3], rxd[3], rxdd[3];
    nodal_gradient(m, y, node, rx);
    nodal_gradient(m, v, node, rxd);
    nodal_gradient(m, a, node, rxdd);
    rod_rereference_rates(m, node, rx, rxd, rxdd, v[o], a[o]);
  }
}

}  // namespace rancf
