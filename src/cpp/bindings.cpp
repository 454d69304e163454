// Python bindings of the compiled core (module rancf._core).  Conversion and forwarding only:
// the holders keep the NumPy arrays alive and expose them to the core as the named structs of
// model.hpp; sizes are checked here so that the core never reads out of bounds.
#include "bindings.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>

#include "assembly.hpp"
#include "cable.hpp"
#include "integrator.hpp"
#include "model.hpp"
#include "rod.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using rancf_bind::expect_size;
using rancf_bind::In;
using rancf_bind::InB;
using rancf_bind::InI;
using rancf_bind::Out;

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
  LoadsHolder loads;
  In mass_band, y_ref;
  rancf::Model m;

  ModelHolder(int kind, int dim, int dpn, int n_el, const rancf::Stiffness& st, CableHolder c,
              BeamHolder b, RodHolder r, SupportsHolder s, LoadsHolder l, In mass, In yref)
      : cable(std::move(c)),
        beam(std::move(b)),
        rod(std::move(r)),
        supports(std::move(s)),
        loads(std::move(l)),
        mass_band(std::move(mass)),
        y_ref(std::move(yref)) {
    if (kind < 0 || kind > 2)
      throw std::invalid_argument("kind: expected 0 (cable), 1 (beam) or 2 (rod)");
    if (dim != 2 && dim != 3) throw std::invalid_argument("dim: expected 2 or 3");
    if (dpn < 1 || 2 * dpn > rancf::kMaxElementDofs)
      throw std::invalid_argument("dpn: too many coordinates per node");
    if (n_el < 1) throw std::invalid_argument("n_el: expected >= 1");
    m.kind = static_cast<rancf::ElementKind>(kind);
    m.dim = dim;
    m.dpn = dpn;
    m.n_el = n_el;
    m.n_nodes = n_el + 1;
    m.stiffness = st;
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
    } else {
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
    expect_size(supports.rot_of_node, ne + 1, "supports.rot_of_node");
    const auto n_rot = supports.rot.size() / static_cast<std::size_t>(dim * dim);
    for (std::size_t i = 0; i <= ne; ++i)
      if (supports.rot_of_node.data()[i] >= static_cast<std::int64_t>(n_rot))
        throw std::invalid_argument("supports.rot_of_node: index out of range");
    m.supports = {supports.fixed.data(), supports.rot_of_node.data(), supports.rot.data()};
    expect_size(loads.f_gravity, n, "loads.f_gravity");
    const std::size_t np = loads.base.size();
    expect_size(loads.f0, np * static_cast<std::size_t>(dim), "loads.f0");
    expect_size(loads.freq, np, "loads.freq");
    for (std::size_t i = 0; i < np; ++i) {
      const std::int64_t b0 = loads.base.data()[i];
      if (b0 < 0 || b0 + dim > static_cast<std::int64_t>(n))
        throw std::invalid_argument("loads.base: index out of range");
    }
    const std::size_t nm = loads.moment_node.size();
    expect_size(loads.moment, 3 * nm, "loads.moment");
    expect_size(loads.moment_freq, nm, "loads.moment_freq");
    if (nm > 0 && m.kind != rancf::ElementKind::rod)
      throw std::invalid_argument("loads.moment: point moments need rod elements");
    for (std::size_t i = 0; i < nm; ++i) {
      const std::int64_t nd = loads.moment_node.data()[i];
      if (nd < 0 || nd > static_cast<std::int64_t>(ne))
        throw std::invalid_argument("loads.moment_node: index out of range");
    }
    m.loads = {loads.f_gravity.data(),   static_cast<int>(np), loads.base.data(),
               loads.f0.data(),          loads.freq.data(),    static_cast<int>(nm),
               loads.moment_node.data(), loads.moment.data(),  loads.moment_freq.data()};
    expect_size(mass_band, static_cast<std::size_t>(2 * m.ku() + 1) * n, "mass_band");
    expect_size(y_ref, n, "y_ref");
    m.mass_band = mass_band.data();
    m.y_ref = y_ref.data();
  }

  [[nodiscard]] std::size_t n() const { return static_cast<std::size_t>(m.n()); }
  [[nodiscard]] std::size_t band_size() const {
    return static_cast<std::size_t>(2 * m.ku() + 1) * n();
  }
};

struct IntegratorHolder {
  rancf::Integrator integ;
  std::size_t n;
  IntegratorHolder(const ModelHolder& mh, const rancf::Scheme& s) : integ(mh.m, s), n(mh.n()) {}
};

}  // namespace

NB_MODULE(_core, mod) {
  mod.doc() = "rancf compiled core: element kernels, banded assembly and LU, generalized-alpha";
  mod.attr("CABLE_ETA") = rancf::kCableEta;
  mod.attr("CABLE_STRAIGHT") = rancf::kCableStraight;

  nb::class_<CableHolder>(mod, "CableData", "Cable quadrature data (see model.hpp).")
      .def(nb::init<In, In, In, In, In, In, In>(), nb::kw_only(), "n1"_a, "n2"_a, "gw"_a, "s0"_a,
           "k0"_a, "j0"_a, "qr"_a);
  nb::class_<BeamHolder>(mod, "BeamData", "Reference chords of beam elements.")
      .def(nb::init<In, In>(), nb::kw_only(), "l0"_a, "d0"_a);
  nb::class_<RodHolder>(mod, "RodData", "Rod quadrature data and nodal reference triads.")
      .def(nb::init<In, In, In, In, In, In, Out, Out>(), nb::kw_only(), "n1"_a, "n2"_a, "xi"_a,
           "gw"_a, "j0"_a, "kref"_a, "tref"_a.noconvert(), "m1ref"_a.noconvert());
  nb::class_<rancf::Stiffness>(mod, "Stiffness", "Section stiffnesses (EA, EI; rod: GJ, EI2, EI3).")
      .def(
          "__init__",
          [](rancf::Stiffness* st, double ea, double ei, double gj, double ei2, double ei3) {
            new (st) rancf::Stiffness{ea, ei, gj, ei2, ei3};
          },
          nb::kw_only(), "ea"_a, "ei"_a = 0.0, "gj"_a = 0.0, "ei2"_a = 0.0, "ei3"_a = 0.0);
  nb::class_<SupportsHolder>(mod, "Supports", "Held coordinates and clamp rotations.")
      .def(nb::init<InB, InI, In>(), nb::kw_only(), "fixed"_a, "rot_of_node"_a, "rot"_a);
  nb::class_<LoadsHolder>(mod, "Loads", "Gravity forces and point loads.")
      .def(nb::init<In, InI, In, In, InI, In, In>(), nb::kw_only(), "f_gravity"_a, "base"_a, "f0"_a,
           "freq"_a, "moment_node"_a, "moment"_a, "moment_freq"_a);

  nb::class_<rancf::Scheme>(mod, "Scheme", "Generalized-alpha constants and Newton settings.")
      .def(
          "__init__",
          [](rancf::Scheme* s, double am, double af, double gamma, double beta, double damping,
             double tol, int max_iter, bool modified) {
            new (s) rancf::Scheme{am, af, gamma, beta, damping, tol, max_iter, modified};
          },
          nb::kw_only(), "alpha_m"_a, "alpha_f"_a, "gamma"_a, "beta"_a, "damping"_a, "tol"_a,
          "max_iter"_a, "modified"_a)
      .def_ro("alpha_m", &rancf::Scheme::alpha_m)
      .def_ro("alpha_f", &rancf::Scheme::alpha_f)
      .def_ro("tol", &rancf::Scheme::tol)
      .def_ro("max_iter", &rancf::Scheme::max_iter);

  nb::class_<ModelHolder>(mod, "Model", "An assembled model (named parts, arrays by reference).")
      .def(nb::init<int, int, int, int, const rancf::Stiffness&, CableHolder, BeamHolder, RodHolder,
                    SupportsHolder, LoadsHolder, In, In>(),
           nb::kw_only(), "kind"_a, "dim"_a, "dpn"_a, "n_el"_a, "stiffness"_a, "cable"_a, "beam"_a,
           "rod"_a, "supports"_a, "loads"_a, "mass_band"_a, "y_ref"_a)
      .def_prop_ro("n", [](const ModelHolder& h) { return h.n(); })
      .def(
          "internal_force",
          [](const ModelHolder& h, In y, Out f) {
            expect_size(y, h.n(), "y");
            expect_size(f, h.n(), "f");
            rancf::assemble(h.m, y.data(), f.data(), nullptr, 0.0);
          },
          "y"_a, "f"_a.noconvert(), "Internal force f = dU/dy (written into f).")
      .def(
          "internal_force_and_tangent",
          [](const ModelHolder& h, In y, Out f, Out ab) {
            expect_size(y, h.n(), "y");
            expect_size(f, h.n(), "f");
            expect_size(ab, h.band_size(), "ab");
            std::fill(ab.data(), ab.data() + ab.size(), 0.0);
            const rancf::BandView k = rancf::numpy_band(ab.data(), h.m.n(), h.m.ku());
            rancf::assemble(h.m, y.data(), f.data(), &k, 1.0);
          },
          "y"_a, "f"_a.noconvert(), "ab"_a.noconvert(),
          "Internal force and tangent stiffness in (2 ku + 1, n) band storage.")
      .def(
          "strain_energy",
          [](const ModelHolder& h, In y) {
            expect_size(y, h.n(), "y");
            return rancf::strain_energy(h.m, y.data());
          },
          "y"_a)
      .def(
          "kinetic_energy",
          [](const ModelHolder& h, In v) {
            expect_size(v, h.n(), "v");
            return rancf::kinetic_energy(h.m, v.data());
          },
          "v"_a)
      .def(
          "gravity_energy",
          [](const ModelHolder& h, In y) {
            expect_size(y, h.n(), "y");
            return rancf::gravity_energy(h.m, y.data());
          },
          "y"_a)
      .def(
          "external_force",
          [](const ModelHolder& h, double t, In y, Out f, bool amplitude) {
            expect_size(y, h.n(), "y");
            expect_size(f, h.n(), "f");
            rancf::external_force(h.m, t, y.data(), f.data(), amplitude);
          },
          "t"_a, "y"_a, "f"_a.noconvert(), "amplitude"_a = false,
          "External force at time t and configuration y (amplitude: harmonic loads at F0).")
      .def(
          "load_stiffness",
          [](const ModelHolder& h, double t, In y, Out ab, bool amplitude) {
            expect_size(y, h.n(), "y");
            expect_size(ab, h.band_size(), "ab");
            std::fill(ab.data(), ab.data() + ab.size(), 0.0);
            const rancf::BandView k = rancf::numpy_band(ab.data(), h.m.n(), h.m.ku());
            rancf::subtract_load_stiffness(h.m, t, y.data(), k, -1.0, amplitude);
          },
          "t"_a, "y"_a, "ab"_a.noconvert(), "amplitude"_a = false,
          "d f_ext / dy (point moments) in (2 ku + 1, n) band storage.")
      .def(
          "rereference",
          [](const ModelHolder& h, In y) {
            expect_size(y, h.n(), "y");
            rancf::rereference(h.m, y.data());
          },
          "y"_a, "Re-reference the rod's nodal triads at configuration y (no-op otherwise).")
      .def(
          "nodal_triads",
          [](const ModelHolder& h, In y, Out t, Out m1) {
            expect_size(y, h.n(), "y");
            const auto nn = static_cast<std::size_t>(h.m.n_nodes);
            expect_size(t, 3 * nn, "t");
            expect_size(m1, 3 * nn, "m1");
            if (h.m.kind != rancf::ElementKind::rod)
              throw std::invalid_argument("nodal_triads: rod models only");
            for (int node = 0; node < h.m.n_nodes; ++node) {
              double rx[3];
              rancf::nodal_gradient(h.m, y.data(), node, rx);
              rancf::rod_nodal_triad(h.m.rod.tref + 3 * node, h.m.rod.m1ref + 3 * node, rx,
                                     y.data()[node * h.m.dpn + 6], t.data() + 3 * node,
                                     m1.data() + 3 * node);
            }
          },
          "y"_a, "t"_a.noconvert(), "m1"_a.noconvert(),
          "Current nodal tangents and directors m1 (rod models), (n_nodes, 3) each.")
      .def(
          "rod_curvatures",
          [](const ModelHolder& h, In y, Out k, Out eps) {
            expect_size(y, h.n(), "y");
            if (h.m.kind != rancf::ElementKind::rod)
              throw std::invalid_argument("rod_curvatures: rod models only");
            const auto npts = static_cast<std::size_t>(h.m.n_el * h.m.rod.n_qp);
            expect_size(k, 3 * npts, "k");
            expect_size(eps, npts, "eps");
            double e[rancf::kMaxElementDofs];
            for (int el = 0; el < h.m.n_el; ++el) {
              for (int i = 0; i < 14; ++i) e[i] = y.data()[el * 7 + i];
              for (int a = 0; a < 2; ++a)
                rancf::nodal_gradient(h.m, y.data(), el + a, e + 7 * a + 3);
              const int o = el * h.m.rod.n_qp;
              rancf::rod_curvatures(h.m, el, e, k.data() + 3 * o, eps.data() + o);
            }
          },
          "y"_a, "k"_a.noconvert(), "eps"_a.noconvert(),
          "Material curvatures (n_el, n_qp, 3) and axial strains (n_el, n_qp) of a rod model.")
      .def(
          "static_newton",
          [](const ModelHolder& h, Out y, double load_factor, double tol, int max_iter) {
            expect_size(y, h.n(), "y");
            rancf::NewtonOutcome r;
            {
              nb::gil_scoped_release release;
              r = rancf::static_newton(h.m, y.data(), load_factor, tol, max_iter);
            }
            return std::make_tuple(r.converged, r.iterations, r.increment);
          },
          "y"_a.noconvert(), "load_factor"_a, "tol"_a, "max_iter"_a,
          "Newton iterations for f_int(y) = load_factor f_ext(y) (loads at their amplitudes); "
          "returns (converged, iterations, increment).");

  nb::class_<IntegratorHolder>(mod, "Integrator", "Generalized-alpha steps on a model.")
      .def(nb::init<const ModelHolder&, const rancf::Scheme&>(), "model"_a, "scheme"_a,
           nb::keep_alive<1, 2>())
      .def_prop_ro("factorizations",
                   [](const IntegratorHolder& h) { return h.integ.factorizations(); })
      .def(
          "step",
          [](IntegratorHolder& h, In y0, In v0, In a0, double t, double dt, Out y1, Out v1,
             Out a1) {
            for (const auto* a : {&y0, &v0, &a0}) expect_size(*a, h.n, "state");
            for (const auto* a : {&y1, &v1, &a1}) expect_size(*a, h.n, "state");
            rancf::StepOutcome r;
            {
              nb::gil_scoped_release release;
              r = h.integ.step(y0.data(), v0.data(), a0.data(), t, dt, y1.data(), v1.data(),
                               a1.data());
            }
            return std::make_tuple(r.converged, r.iterations);
          },
          "y0"_a, "v0"_a, "a0"_a, "t"_a, "h"_a, "y1"_a.noconvert(), "v1"_a.noconvert(),
          "a1"_a.noconvert(), "One step; returns (converged, iterations).")
      .def(
          "run",
          [](IntegratorHolder& h, Out y, Out v, Out a, double t0, double dt, std::int64_t n_steps,
             std::int64_t out_every, std::int64_t done_before, double max_seconds, Out out_y,
             Out out_v, Out out_e) {
            for (const auto* x : {&y, &v, &a}) expect_size(*x, h.n, "state");
            if (out_every < 1 || n_steps < 0 || done_before < 0 || done_before >= out_every)
              throw std::invalid_argument("run: bad step counts");
            const auto n_out = static_cast<std::size_t>((done_before + n_steps) / out_every);
            expect_size(out_y, n_out * h.n, "out_y");
            expect_size(out_v, n_out * h.n, "out_v");
            expect_size(out_e, n_out * 3, "out_e");
            rancf::RunOutcome r;
            {
              nb::gil_scoped_release release;
              r = h.integ.run(y.data(), v.data(), a.data(), t0, dt, n_steps, out_every, done_before,
                              max_seconds, out_y.data(), out_v.data(), out_e.data());
            }
            return std::make_tuple(r.steps, r.converged, r.iterations, r.stored);
          },
          "y"_a.noconvert(), "v"_a.noconvert(), "a"_a.noconvert(), "t0"_a, "h"_a, "n_steps"_a,
          "out_every"_a, "done_before"_a, "max_seconds"_a, "out_y"_a.noconvert(),
          "out_v"_a.noconvert(), "out_e"_a.noconvert(),
          "Fixed steps (returning after about max_seconds of wall time); returns (steps, "
          "converged, iterations, stored).")
      .def(
          "initial_acceleration",
          [](IntegratorHolder& h, In y, In v, double t, Out a) {
            for (const auto* x : {&y, &v}) expect_size(*x, h.n, "state");
            expect_size(a, h.n, "a");
            h.integ.initial_acceleration(y.data(), v.data(), t, a.data());
          },
          "y"_a, "v"_a, "t"_a, "a"_a.noconvert());

  rancf_bind::bind_functions(mod);
}
