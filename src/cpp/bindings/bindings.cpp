// Python bindings of the compiled core (module rancf._core).  Conversion and forwarding only:
// the holders keep the NumPy arrays alive and expose them to the core as the named structs of
// model.hpp; sizes are checked here so that the core never reads out of bounds.
#include "bindings/bindings.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "bindings/bindings_model.hpp"
#include "bodies/assembly.hpp"
#include "bodies/inertia.hpp"
#include "bodies/model.hpp"
#include "bodies/sections.hpp"
#include "elements/cable.hpp"
#include "elements/registry.hpp"
#include "elements/rod.hpp"
#include "solvers/integrator.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using rancf_bind::AxialLawHolder;
using rancf_bind::BeamHolder;
using rancf_bind::CableHolder;
using rancf_bind::expect_size;
using rancf_bind::In;
using rancf_bind::InB;
using rancf_bind::InI;
using rancf_bind::LoadsHolder;
using rancf_bind::ModelHolder;
using rancf_bind::Out;
using rancf_bind::ReductionHolder;
using rancf_bind::RodHolder;
using rancf_bind::SupportsHolder;

/// The records a model is made of (element data, stiffness, supports, loads) and the scheme.
void bind_model_data(nb::module_& mod) {
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
          [](rancf::Stiffness* st, double ea, double ei, double gj, double ei2, double ei3,
             bool engineering, double damping_axial, double damping_bending,
             double damping_torsion) {
            for (const double c : {damping_axial, damping_bending, damping_torsion})
              if (!(c >= 0.0 && std::isfinite(c)))
                throw std::invalid_argument("Stiffness: damping coefficients must be finite >= 0");
            new (st) rancf::Stiffness{
                ea, ei, gj, ei2, ei3, engineering, damping_axial, damping_bending, damping_torsion};
          },
          nb::kw_only(), "ea"_a, "ei"_a = 0.0, "gj"_a = 0.0, "ei2"_a = 0.0, "ei3"_a = 0.0,
          "engineering"_a = false, "damping_axial"_a = 0.0, "damping_bending"_a = 0.0,
          "damping_torsion"_a = 0.0)
      .def_ro("ea", &rancf::Stiffness::ea)
      .def_ro("ei", &rancf::Stiffness::ei)
      .def_ro("gj", &rancf::Stiffness::gj)
      .def_ro("ei2", &rancf::Stiffness::ei2)
      .def_ro("ei3", &rancf::Stiffness::ei3)
      .def_ro("engineering", &rancf::Stiffness::engineering)
      .def_ro("damping_axial", &rancf::Stiffness::damping_axial)
      .def_ro("damping_bending", &rancf::Stiffness::damping_bending)
      .def_ro("damping_torsion", &rancf::Stiffness::damping_torsion);
  nb::class_<AxialLawHolder>(mod, "AxialLaw",
                             "A tension law T(e) of the engineering strain: a C1 piecewise cubic "
                             "(elements/tension_law.hpp).")
      .def(
          "__init__",
          [](AxialLawHolder* h, In breaks, In coef) {
            const std::size_t k = breaks.size();
            if (k < 2) throw std::invalid_argument("AxialLaw.breaks: expected >= 2 values");
            expect_size(coef, 4 * (k - 1), "AxialLaw.coef");
            for (std::size_t i = 0; i + 1 < k; ++i)
              if (!(breaks.data()[i] < breaks.data()[i + 1]))
                throw std::invalid_argument("AxialLaw.breaks: expected increasing values");
            for (std::size_t i = 0; i < coef.size(); ++i)
              if (!std::isfinite(coef.data()[i]))
                throw std::invalid_argument("AxialLaw.coef: expected finite values");
            new (h) AxialLawHolder{breaks, coef};
          },
          nb::kw_only(), "breaks"_a, "coef"_a)
      .def_ro("breaks", &AxialLawHolder::breaks)
      .def_ro("coef", &AxialLawHolder::coef);
  nb::class_<rancf::SectionInertia>(mod, "SectionInertia",
                                    "Rotary inertia of rod sections per length (rho Ip, rho I).")
      .def(
          "__init__",
          [](rancf::SectionInertia* r, double polar, double bend) {
            new (r) rancf::SectionInertia{polar, bend};
          },
          nb::kw_only(), "polar"_a = 0.0, "bend"_a = 0.0)
      .def_ro("polar", &rancf::SectionInertia::polar)
      .def_ro("bend", &rancf::SectionInertia::bend);
  nb::class_<SupportsHolder>(mod, "Supports", "Held coordinates and clamp rotations.")
      .def(nb::init<InB, InI, In>(), nb::kw_only(), "fixed"_a, "rot_of_node"_a, "rot"_a);
  nb::class_<ReductionHolder>(mod, "Reduction",
                              "Reduced coordinates: element and node maps (n_y = 0: none).")
      .def(
          "__init__",
          [](ReductionHolder* r, int n_y, int ku, int width, int node_width, InI el_start,
             In el_map, InI node_start, In node_map, InI twist) {
            new (r) ReductionHolder{n_y,    ku,         width,    node_width, el_start,
                                    el_map, node_start, node_map, twist};
          },
          nb::kw_only(), "n_y"_a, "ku"_a, "width"_a, "node_width"_a, "el_start"_a, "el_map"_a,
          "node_start"_a, "node_map"_a, "twist"_a);
  nb::class_<rancf_bind::ShellHolder>(
      mod, "ShellData",
      "A shell model's elements (ShellKernel) and its supports' node bases (y_k = B q_k).")
      .def(
          "__init__",
          [](rancf_bind::ShellHolder* h, nb::object elements, InI node_rot, In node_basis) {
            new (h) rancf_bind::ShellHolder{std::move(elements), node_rot, node_basis};
          },
          nb::kw_only(), "elements"_a, "node_rot"_a, "node_basis"_a);
  nb::class_<LoadsHolder>(mod, "Loads", "Gravity forces and point loads.")
      .def(nb::init<In, InI, In, In, InI, In, In>(), nb::kw_only(), "f_gravity"_a, "base"_a, "f0"_a,
           "freq"_a, "moment_node"_a, "moment"_a, "moment_freq"_a);

  nb::class_<rancf::Scheme>(mod, "Scheme", "Generalized-alpha constants and Newton settings.")
      .def(
          "__init__",
          [](rancf::Scheme* s, double am, double af, double gamma, double beta, double damping,
             double tol, int max_iter, bool modified, bool chord) {
            new (s) rancf::Scheme{am, af, gamma, beta, damping, tol, max_iter, modified, chord};
          },
          nb::kw_only(), "alpha_m"_a, "alpha_f"_a, "gamma"_a, "beta"_a, "damping"_a, "tol"_a,
          "max_iter"_a, "modified"_a, "chord"_a = false)
      .def_ro("alpha_m", &rancf::Scheme::alpha_m)
      .def_ro("alpha_f", &rancf::Scheme::alpha_f)
      .def_ro("tol", &rancf::Scheme::tol)
      .def_ro("max_iter", &rancf::Scheme::max_iter);
}

/// The assembled model: forces, tangents, energies and a rod's frames and curvatures.
nb::class_<ModelHolder> bind_model(nb::module_& mod) {
  auto model_cls =
      nb::class_<ModelHolder>(mod, "Model",
                              "An assembled model (named parts, arrays by reference).")
          .def(nb::init<int, int, int, int, const rancf::Stiffness&, CableHolder, BeamHolder,
                        RodHolder, SupportsHolder, LoadsHolder, In, In,
                        const rancf::SectionInertia&, bool, ReductionHolder,
                        std::optional<AxialLawHolder>, std::optional<rancf_bind::ShellHolder>>(),
               nb::kw_only(), "kind"_a, "dim"_a, "dpn"_a, "n_el"_a, "stiffness"_a, "cable"_a,
               "beam"_a, "rod"_a, "supports"_a, "loads"_a, "mass_band"_a, "y_ref"_a,
               "rotary"_a = rancf::SectionInertia{}, "closed"_a = false, "reduction"_a,
               "axial_law"_a = nb::none(), "shell"_a = nb::none())
          .def_prop_ro("n", [](const ModelHolder& h) { return h.n(); })
          .def_prop_rw(
              "axial_stiffness", [](const ModelHolder& h) { return h.m.stiffness.ea; },
              [](ModelHolder& h, double ea) {
                if (!(ea > 0.0 && std::isfinite(ea)))
                  throw std::invalid_argument("axial_stiffness: a finite number > 0");
                h.m.stiffness.ea = ea;
              },
              "EA [N] the element kernels read at every evaluation (the static solver's axial "
              "stiffness continuation lowers it for a while: rancf.solvers.axial_continuation).")
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
              "damping_force",
              [](const ModelHolder& h, In y, In v, Out f, std::optional<Out> ab, double ck,
                 double cv) {
                expect_size(y, h.n(), "y");
                expect_size(v, h.n(), "v");
                expect_size(f, h.n(), "f");
                std::fill(f.data(), f.data() + f.size(), 0.0);
                if (!ab)
                  return rancf::assemble_damping(h.m, y.data(), v.data(), 0.0, 0.0, f.data(),
                                                 nullptr);
                expect_size(*ab, h.band_size(), "ab");
                std::fill(ab->data(), ab->data() + ab->size(), 0.0);
                const rancf::BandView k = rancf::numpy_band(ab->data(), h.m.n(), h.m.ku());
                rancf::assemble_damping(h.m, y.data(), v.data(), ck, cv, f.data(), &k);
              },
              "y"_a, "v"_a, "f"_a.noconvert(), "ab"_a.noconvert() = nb::none(), "ck"_a = 1.0,
              "cv"_a = 0.0,
              "Kelvin-Voigt strain-rate damping force f_d(y, v) (docs/derivations/"
              "strain-rate-damping.md) into f and, with ab, its Jacobian ck df_d/dy + cv df_d/dv "
              "in (2 ku + 1, n) band storage.")
          .def(
              "strain_energy",
              [](const ModelHolder& h, In y) {
                expect_size(y, h.n(), "y");
                return rancf::strain_energy(h.m, y.data());
              },
              "y"_a)
          .def(
              "kinetic_energy",
              [](const ModelHolder& h, In y, In v) {
                expect_size(y, h.n(), "y");
                expect_size(v, h.n(), "v");
                return rancf::kinetic_energy(h.m, y.data(), v.data());
              },
              "y"_a, "v"_a, "Kinetic energy at (y, v), rods' rotary part included.")
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
              [](const ModelHolder& h, In y, std::optional<Out> v, std::optional<Out> a,
                 std::optional<Out> w) {
                expect_size(y, h.n(), "y");
                if (v.has_value() != a.has_value() || (w && !v))
                  throw std::invalid_argument("rereference: give v and a (and w), or neither");
                if (w) {  // w's twist as a's (its own rates discarded: v is carried below)
                  expect_size(*w, h.n(), "w");
                  std::vector<double> vw(v->data(), v->data() + h.n());
                  rancf::rereference_rates(h.m, y.data(), vw.data(), w->data());
                }
                if (v) {
                  expect_size(*v, h.n(), "v");
                  expect_size(*a, h.n(), "a");
                  rancf::rereference_rates(h.m, y.data(), v->data(), a->data());
                }
                rancf::rereference(h.m, y.data());
              },
              "y"_a, "v"_a.noconvert() = nb::none(), "a"_a.noconvert() = nb::none(),
              "w"_a.noconvert() = nb::none(),
              "Re-reference the rod's nodal triads at configuration y (no-op otherwise); with v "
              "and a (updated in place) the twist rates keep the spin; w (algorithmic "
              "accelerations) is carried as a.")
          .def(
              "nodal_triads",
              [](const ModelHolder& h, In y, Out t, Out m1) {
                expect_size(y, h.n(), "y");
                const auto nn = static_cast<std::size_t>(h.m.n_nodes);
                expect_size(t, 3 * nn, "t");
                expect_size(m1, 3 * nn, "m1");
                if (!rancf::kernel_for(h.m).triads)
                  throw std::invalid_argument("nodal_triads: rod models only");
                for (int node = 0; node < h.m.n_nodes; ++node) {
                  double rx[3];
                  rancf::nodal_gradient(h.m, y.data(), node, rx);
                  rancf::rod_nodal_triad(h.m.rod.tref + 3 * node, h.m.rod.m1ref + 3 * node, rx,
                                         y.data()[rancf::twist_index(h.m, node)],
                                         t.data() + 3 * node, m1.data() + 3 * node);
                }
              },
              "y"_a, "t"_a.noconvert(), "m1"_a.noconvert(),
              "Current nodal tangents and directors m1 (rod models), (n_nodes, 3) each.")
          .def(
              "rod_curvatures",
              [](const ModelHolder& h, In y, Out k, Out eps) {
                expect_size(y, h.n(), "y");
                if (!rancf::kernel_for(h.m).triads)
                  throw std::invalid_argument("rod_curvatures: rod models only");
                const auto npts = static_cast<std::size_t>(h.m.n_el * h.m.rod.n_qp);
                expect_size(k, 3 * npts, "k");
                expect_size(eps, npts, "eps");
                double e[rancf::kMaxElementDofs];
                for (int el = 0; el < h.m.n_el; ++el) {
                  rancf::element_coordinates(h.m, y.data(), el, e);
                  const int o = el * h.m.rod.n_qp;
                  rancf::rod_curvatures(h.m, el, e, k.data() + 3 * o, eps.data() + o);
                }
              },
              "y"_a, "k"_a.noconvert(), "eps"_a.noconvert(),
              "Material curvatures (n_el, n_qp, 3) and axial strains (n_el, n_qp) of a rod model.")
          .def(
              "section_strains",
              [](const ModelHolder& h, In xi, In n1, In n2, In ref, In y, Out out) {
                // xi (n); n1, n2 (n_el, n, 4); ref (n_el, n): s0 (cable) or j0 (rod); out
                // (n_el, n, section_width); k states y (k, n_dofs): out (k, n_el, n, width)
                const std::size_t nd = h.n(), k = nd > 0 ? y.size() / nd : 0;
                if (k == 0 || y.size() != k * nd) expect_size(y, nd, "y");
                const std::size_t np = xi.size(), ne = static_cast<std::size_t>(h.m.n_el);
                const bool pts = rancf::kernel_for(h.m).centre_line;
                expect_size(n1, pts ? ne * np * 4 : n1.size(), "n1");
                expect_size(n2, pts ? ne * np * 4 : n2.size(), "n2");
                expect_size(ref, pts ? ne * np : ref.size(), "ref");
                const auto w = static_cast<std::size_t>(rancf::section_width(h.m));
                expect_size(out, k * ne * np * w, "out");
                const rancf::SamplePoints p{static_cast<int>(np), xi.data(), n1.data(), n2.data(),
                                            ref.data()};
                nb::gil_scoped_release release;
                for (std::size_t i = 0; i < k; ++i)
                  rancf::section_strains(h.m, p, y.data() + i * nd, out.data() + i * ne * np * w);
              },
              "xi"_a, "n1"_a, "n2"_a, "ref"_a, "y"_a, "out"_a.noconvert(),
              "Strains and curvatures at sample points of every element (see sections.hpp), "
              "of one state or k stacked ones.");
  return model_cls;
}

}  // namespace

NB_MODULE(_core, mod) {
  mod.doc() = "rancf compiled core: element kernels, banded assembly and LU, generalized-alpha";
  mod.attr("CABLE_ETA") = rancf::kCableEta;
  mod.attr("CABLE_STRAIGHT") = rancf::kCableStraight;

  bind_model_data(mod);
  auto model_cls = bind_model(mod);
  rancf_bind::bind_inertia(model_cls);

  rancf_bind::bind_functions(mod);
  rancf_bind::bind_contact(mod);
  rancf_bind::bind_system(mod);
  rancf_bind::bind_shell(mod);
}
