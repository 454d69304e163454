// The holders of the model's arrays and the model as the core sees it (shared by the binding
// files; conversion only): the holders keep the NumPy arrays alive and expose them to the core as
// the named structs of model.hpp; sizes are checked here so that the core never reads out of
// bounds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "bindings/bindings.hpp"
#include "bodies/model.hpp"
#include "elements/registry.hpp"
#include "elements/shell.hpp"
#include "solvers/integrator.hpp"

namespace rancf_bind {

struct CableHolder {
  In n1, n2, gw, s0, k0, j0, qr;
};
struct BeamHolder {
  In l0, d0;
};
struct RodHolder {
  In n1, n2, xi, gw, j0, kref;
  Out tref, m1ref;  // re-referenced in place by the core
};
struct SupportsHolder {
  InB fixed;
  InI rot_of_node;
  In rot;
};
struct ReductionHolder {
  int n_y = 0, ku = 0, width = 0, node_width = 0;
  InI el_start;
  In el_map;
  InI node_start;
  In node_map;
  InI twist;
};
/// A shell model's elements (rancf._core.ShellKernel, kept alive) and its supports' node bases.
struct ShellHolder {
  nb::object elements;
  InI node_rot;
  In node_basis;
};
struct LoadsHolder {
  In f_gravity;
  InI base;
  In f0, freq;
  InI moment_node;
  In moment, moment_freq;
};

/// A model: the holders plus the core view on them.
struct ModelHolder {
  CableHolder cable;
  BeamHolder beam;
  RodHolder rod;
  SupportsHolder supports;
  ReductionHolder reduction;
  LoadsHolder loads;
  In mass_band, y_ref;
  std::optional<AxialLawHolder> axial_law;
  std::optional<ShellHolder> shell;
  rancf::Model m;

  ModelHolder(int kind, int dim, int dpn, int n_el, const rancf::Stiffness& st, CableHolder c,
              BeamHolder b, RodHolder r, SupportsHolder s, LoadsHolder l, In mass, In yref,
              const rancf::SectionInertia& rotary, bool closed, ReductionHolder red,
              std::optional<AxialLawHolder> law = std::nullopt,
              std::optional<ShellHolder> shell_data = std::nullopt)
      : cable(std::move(c)),
        beam(std::move(b)),
        rod(std::move(r)),
        supports(std::move(s)),
        reduction(std::move(red)),
        loads(std::move(l)),
        mass_band(std::move(mass)),
        y_ref(std::move(yref)),
        axial_law(std::move(law)),
        shell(std::move(shell_data)) {
    if (kind < 0 || kind > 3)
      throw std::invalid_argument("kind: expected 0 (cable), 1 (beam), 2 (rod) or 3 (shell)");
    if (dim != 2 && dim != 3) throw std::invalid_argument("dim: expected 2 or 3");
    if (dpn < 1 || (kind != 3 && 2 * dpn > rancf::kMaxElementDofs))
      throw std::invalid_argument("dpn: too many coordinates per node");
    if (n_el < 1) throw std::invalid_argument("n_el: expected >= 1");
    m.kind = static_cast<rancf::ElementKind>(kind);
    m.dim = dim;
    m.dpn = dpn;
    m.n_el = n_el;
    m.n_nodes = n_el + 1;
    if (kind == 3)
      set_shell();
    else if (shell)
      throw std::invalid_argument("shell: only a shell model (kind 3) has it");
    m.closed = closed;
    m.stiffness = st;
    m.stiffness.axial_law = law_table(axial_law ? &*axial_law : nullptr);
    if (m.stiffness.axial_law.active() && m.kind == rancf::ElementKind::beam)
      throw std::invalid_argument("axial_law: cable and rod elements only");
    set_reduction();
    const auto n = static_cast<std::size_t>(m.n()), ne = static_cast<std::size_t>(n_el);
    if (m.kind == rancf::ElementKind::cable) {
      if (dpn != 2 * dim)
        throw std::invalid_argument("dpn: a cable has 2 dim coordinates per node");
      const std::size_t nq = cable.gw.size();
      expect_size(cable.n1, ne * nq * 4, "cable.n1");
      expect_size(cable.n2, ne * nq * 4, "cable.n2");
      for (const auto* a : {&cable.s0, &cable.k0, &cable.j0, &cable.qr})
        expect_size(*a, ne * nq, "cable quadrature data");
      m.cable = {static_cast<int>(nq), cable.n1.data(), cable.n2.data(), cable.gw.data(),
                 cable.s0.data(),      cable.k0.data(), cable.j0.data(), cable.qr.data()};
    } else if (m.kind == rancf::ElementKind::beam) {
      if (dim != 2 || dpn != 3) throw std::invalid_argument("beam: planar, 3 coordinates per node");
      expect_size(beam.l0, ne, "beam.l0");
      expect_size(beam.d0, 2 * ne, "beam.d0");
      m.beam = {beam.l0.data(), beam.d0.data()};
    } else if (m.kind == rancf::ElementKind::rod) {
      if (dim != 3 || dpn != 7) throw std::invalid_argument("rod: spatial, 7 coordinates per node");
      const std::size_t nq = rod.gw.size();
      expect_size(rod.xi, nq, "rod.xi");
      expect_size(rod.n1, ne * nq * 4, "rod.n1");
      expect_size(rod.n2, ne * nq * 4, "rod.n2");
      expect_size(rod.j0, ne * nq, "rod.j0");
      expect_size(rod.kref, ne * nq * 3, "rod.kref");
      expect_size(rod.tref, 3 * (ne + 1), "rod.tref");
      expect_size(rod.m1ref, 3 * (ne + 1), "rod.m1ref");
      m.rod = {static_cast<int>(nq), rod.n1.data(),   rod.n2.data(),
               rod.xi.data(),        rod.gw.data(),   rod.j0.data(),
               rod.kref.data(),      rod.tref.data(), rod.m1ref.data()};
    }
    expect_size(supports.fixed, n, "supports.fixed");
    const auto nn = static_cast<std::size_t>(m.n_nodes);
    expect_size(supports.rot_of_node, 2 * nn, "supports.rot_of_node");
    const auto n_rot = supports.rot.size() / static_cast<std::size_t>(dim * dim);
    for (std::size_t i = 0; i < 2 * nn; ++i) {
      const std::int64_t r = supports.rot_of_node.data()[i];
      if (r >= static_cast<std::int64_t>(n_rot))
        throw std::invalid_argument("supports.rot_of_node: index out of range");
      if (r >= 0 && m.connectivity.nodes_of != nullptr)
        throw std::invalid_argument("supports.rot_of_node: a shell has no rotated blocks (-1)");
    }
    m.supports = {supports.fixed.data(), supports.rot_of_node.data(), supports.rot.data()};
    expect_size(loads.f_gravity, n, "loads.f_gravity");
    const std::size_t np = loads.base.size();
    expect_size(loads.f0, np * static_cast<std::size_t>(dim), "loads.f0");
    expect_size(loads.freq, np, "loads.freq");
    const auto nq = static_cast<std::int64_t>(nn * static_cast<std::size_t>(dpn));
    for (std::size_t i = 0; i < np; ++i) {  // node dpn (reduced: of the full coordinates)
      const std::int64_t b0 = loads.base.data()[i];
      if (b0 < 0 || b0 + dim > (m.reduced() ? nq : static_cast<std::int64_t>(n)) ||
          (m.reduced() && b0 % dpn != 0))
        throw std::invalid_argument("loads.base: index out of range");
    }
    const std::size_t nm = loads.moment_node.size();
    expect_size(loads.moment, 3 * nm, "loads.moment");
    expect_size(loads.moment_freq, nm, "loads.moment_freq");
    if (nm > 0 && !rancf::kernel_for(m).triads)
      throw std::invalid_argument("loads.moment: point moments need rod elements");
    for (std::size_t i = 0; i < nm; ++i) {
      const std::int64_t nd = loads.moment_node.data()[i];
      if (nd < 0 || nd >= static_cast<std::int64_t>(nn))
        throw std::invalid_argument("loads.moment_node: index out of range");
    }
    m.loads = {loads.f_gravity.data(),   static_cast<int>(np), loads.base.data(),
               loads.f0.data(),          loads.freq.data(),    static_cast<int>(nm),
               loads.moment_node.data(), loads.moment.data(),  loads.moment_freq.data()};
    expect_size(mass_band, static_cast<std::size_t>(2 * m.ku() + 1) * n, "mass_band");
    expect_size(y_ref, n, "y_ref");
    m.mass_band = mass_band.data();
    m.y_ref = y_ref.data();
    if (!(rotary.polar >= 0.0 && rotary.bend >= 0.0))  // also rejects NaN
      throw std::invalid_argument("rotary: expected finite moments >= 0");
    if ((rotary.polar > 0.0 || rotary.bend > 0.0) && !rancf::kernel_for(m).triads)
      throw std::invalid_argument("rotary: a rotary inertia needs rod elements");
    m.rotary = rotary;
  }

  /// A shell model's elements (rancf._core.ShellKernel) and their connectivity (4 nodes of 12
  /// coordinates an element), the half bandwidth from the largest node span of an element.
  void set_shell() {
    rancf::ShellElements* el = nullptr;
    if (!shell || !nb::try_cast(shell->elements, el) || el == nullptr)
      throw std::invalid_argument("shell: a shell model needs its ShellData (a ShellKernel)");
    if (m.dim != 3 || m.dpn != 12)
      throw std::invalid_argument("shell: spatial, 12 coordinates per node");
    if (el->n_el() != m.n_el)
      throw std::invalid_argument("n_el: expected the shell's " + std::to_string(el->n_el()));
    if (reduction.n_y != 0) throw std::invalid_argument("reduction: a shell has none (n_y 0)");
    const auto& conn = el->input().connectivity;
    int span = 0;
    for (std::size_t e = 0; e < conn.size(); e += 4) {
      const auto [lo, hi] = std::minmax_element(conn.begin() + static_cast<std::ptrdiff_t>(e),
                                                conn.begin() + static_cast<std::ptrdiff_t>(e + 4));
      span = std::max(span, static_cast<int>(*hi - *lo));
    }
    m.n_nodes = el->input().n_nodes;
    const auto nn = static_cast<std::size_t>(m.n_nodes), b2 = static_cast<std::size_t>(144);
    expect_size(shell->node_rot, nn, "shell.node_rot");
    if (shell->node_basis.size() % b2 != 0)
      throw std::invalid_argument("shell.node_basis: expected (n_rot, 12, 12) values");
    const auto n_rot = static_cast<std::int64_t>(shell->node_basis.size() / b2);
    for (std::size_t k = 0; k < nn; ++k)
      if (shell->node_rot.data()[k] < -1 || shell->node_rot.data()[k] >= n_rot)
        throw std::invalid_argument("shell.node_rot: index out of range");
    m.shell = {el, shell->node_rot.data(), shell->node_basis.data()};
    m.connectivity = {4, conn.data(), m.dpn * (span + 1) - 1};
  }

  /// The reduction's view (sizes and index ranges checked); none if n_y == 0.
  void set_reduction() {
    const ReductionHolder& r = reduction;
    if (r.n_y == 0) return;
    const int ne = m.n_el, nn = m.n_nodes, nde = 2 * m.dpn;
    if (r.n_y < 0 || r.width < 1 || r.width > rancf::kMaxWindow || r.node_width < 1 ||
        r.node_width > rancf::kMaxWindow || r.ku < r.width - 1 || r.ku >= r.n_y)
      throw std::invalid_argument("reduction: inconsistent sizes");
    const auto sz = [](int k) { return static_cast<std::size_t>(k); };
    expect_size(r.el_start, sz(ne), "reduction.el_start");
    expect_size(r.el_map, sz(ne * nde * r.width), "reduction.el_map");
    expect_size(r.node_start, sz(nn), "reduction.node_start");
    expect_size(r.node_map, sz(nn * m.dpn * r.node_width), "reduction.node_map");
    for (int e = 0; e < ne; ++e) {
      const std::int64_t s0 = r.el_start.data()[e];
      if (s0 < 0 || s0 + r.width > r.n_y)
        throw std::invalid_argument("reduction.el_start: window out of range");
    }
    for (int k = 0; k < nn; ++k) {
      const std::int64_t s0 = r.node_start.data()[k];
      if (s0 < 0 || s0 + r.node_width > r.n_y)
        throw std::invalid_argument("reduction.node_start: window out of range");
    }
    const std::int64_t* tw = nullptr;
    if (rancf::kernel_for(m).triads) {
      expect_size(r.twist, sz(nn), "reduction.twist");
      for (int k = 0; k < nn; ++k)
        if (r.twist.data()[k] < 0 || r.twist.data()[k] >= r.n_y)
          throw std::invalid_argument("reduction.twist: index out of range");
      tw = r.twist.data();
    }
    m.reduction = {r.n_y,
                   r.ku,
                   r.width,
                   r.el_start.data(),
                   r.el_map.data(),
                   r.node_width,
                   r.node_start.data(),
                   r.node_map.data(),
                   tw};
  }

  [[nodiscard]] std::size_t n() const { return static_cast<std::size_t>(m.n()); }
  [[nodiscard]] std::size_t band_size() const {
    return static_cast<std::size_t>(2 * m.ku() + 1) * n();
  }
};

/// Methods of Model for the rotary inertia (bindings_inertia.cpp).
void bind_inertia(nb::class_<ModelHolder>& cls);

}  // namespace rancf_bind
