// Spatial Kirchhoff rod with torsion on the RANCF centerline (docs/derivations/rod.md; Meier, Popp
// & Wall 2014).
//
// The element math is in rod_kernel.hpp and the rod_*.hpp headers it includes (derivation:
// docs/derivations/rod-kernel.md); this file connects it to the model: element inputs from RodData,
// the registry entry, point moments and the re-referencing of the nodal triads after converged
// steps.
//
// Re-referencing keeps the nodal twist phi as a degree of freedom that accumulates: the reference
// director becomes u = SR(t_ref -> t) m1_ref (the untwisted transported director) and t_ref <- t.
// The nodal triad m1 = cos(phi) u + sin(phi) t x u is unchanged, so the state is the same, and phi
// stays the twist of the cross-section about the tangent relative to the reference director
// transported along the motion by smallest rotations (the twist sensor).
#include "elements/rod.hpp"

#include <cmath>
#include <vector>

#include "bodies/sections.hpp"
#include "elements/registry.hpp"
#include "elements/rod_damping.hpp"
#include "elements/rod_inertia.hpp"
#include "elements/rod_kernel.hpp"

namespace rancf {
namespace {

rod::ElementInput rod_input(const Model& m, int el) {
  const RodData& r = m.rod;
  const int nq = r.n_qp;
  return {r.n1 + el * nq * 4,
          r.n2 + el * nq * 4,
          r.xi,
          r.gw,
          r.j0 + el * nq,
          r.kref + el * nq * 3,
          nq,
          r.tref + el * 3,
          r.m1ref + el * 3,
          r.tref + (el + 1) * 3,
          r.m1ref + (el + 1) * 3};
}

rod::InertiaCoef rod_inertia_coef(const Model& m) { return {m.rotary.polar, m.rotary.bend}; }

// The element input with the current nodal tangents as references (tr[6]: storage).
rod::ElementInput current_input(const Model& m, int el, const double* e, double* tr) {
  rod::ElementInput in = rod_input(m, el);
  for (int a = 0; a < 2; ++a) {
    const double* x = e + 7 * a + 3;
    const double s = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int i = 0; i < 3; ++i) tr[3 * a + i] = x[i] / s;
  }
  in.tref_a = tr;
  in.tref_b = tr + 3;
  return in;
}

rod::Stiffness rod_stiffness(const Model& m) {
  return {m.stiffness.ea, m.stiffness.gj, m.stiffness.ei2, m.stiffness.ei3, m.stiffness.axial_law};
}

void rod_forces(const Model& m, int el, const double* e, double* fe, double* ke) {
  rod::forces(rod_input(m, el), rod_stiffness(m), e, fe, ke);
}

double rod_energy(const Model& m, int el, const double* e) {
  return rod::energy(rod_input(m, el), rod_stiffness(m), e);
}

// Kelvin-Voigt strain-rate damping (rod_damping.hpp).
void rod_damping(const Model& m, int el, const double* e, const double* ed, double ck, double cv,
                 double* fe, double* ke) {
  const Stiffness& st = m.stiffness;
  rod::damping(rod_input(m, el), {st.damping_axial, st.damping_torsion, st.damping_bending}, e, ed,
               ck, cv, fe, ke);
}

}  // namespace

const ElementKernel rod_kernel = {
    rod_forces,      rod_energy,           rod_damping,    section_rod, 4,
    /*triads=*/true, /*centre_line=*/true, /*winch=*/false};

void rod_curvatures(const Model& m, int el, const double* e, double* k, double* eps) {
  rod::curvatures(rod_input(m, el), e, k, eps);
}

void rod_point_strains(const Model& m, int el, const double* e, int n, const double* xi,
                       const double* n1, const double* n2, const double* j0, double* out) {
  const RodData& r = m.rod;
  const rod::ElementInput in{n1,
                             n2,
                             xi,
                             nullptr,
                             j0,
                             nullptr,
                             n,
                             r.tref + el * 3,
                             r.m1ref + el * 3,
                             r.tref + (el + 1) * 3,
                             r.m1ref + (el + 1) * 3};
  std::vector<double> k(static_cast<std::size_t>(3 * n)), eps(static_cast<std::size_t>(n));
  rod::curvatures(in, e, k.data(), eps.data());
  for (int q = 0; q < n; ++q) {
    const auto uq = static_cast<std::size_t>(q);
    out[4 * q] = eps[uq];
    for (int i = 0; i < 3; ++i) out[4 * q + 1 + i] = k[3 * uq + static_cast<std::size_t>(i)];
  }
}

void rod_nodal_triad(const double* tref, const double* m1ref, const double* rx, double phi,
                     double* t, double* m1) {
  rod::nodal_triad(tref, m1ref, rx, phi, t, m1);
}

void rod_moment_load(const Model& m, int node, const double* moment, const double* rx, double* g,
                     double* kl) {
  rod::moment_load(moment, m.rod.tref + 3 * node, m.rod.m1ref + 3 * node, rx, g, kl);
}

void rod_inertia(const Model& m, int el, const double* e, const double* ed, const double* edd,
                 double damping, double ck, double cv, double ca, double* fe, double* ke) {
  rod::inertia(rod_input(m, el), rod_inertia_coef(m), e, ed, edd, {damping, ck, cv, ca}, fe, ke);
}

double rod_rotary_energy(const Model& m, int el, const double* e, const double* ed, bool current) {
  double tr[6];
  const rod::ElementInput in = current ? current_input(m, el, e, tr) : rod_input(m, el);
  return rod::rotary_energy(in, rod_inertia_coef(m), e, ed);
}

void rod_rotary_momentum(const Model& m, int el, const double* e, const double* ed, bool current,
                         double* out) {
  double tr[6];
  const rod::ElementInput in = current ? current_input(m, el, e, tr) : rod_input(m, el);
  rod::rotary_momentum(in, rod_inertia_coef(m), e, ed, out);
}

void rod_rereference_rates(const Model& m, int node, const double* rx, const double* rxd,
                           const double* rxdd, double& phid, double& phidd) {
  rod::rereference_rates(m.rod.tref + 3 * node, rx, rxd, rxdd, phid, phidd);
}

}  // namespace rancf
