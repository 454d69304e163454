// Python bindings of systems (rancf._core.System, SystemIntegrator): conversion and forwarding
// only.  A system's parts arrive as lists of named records read into the structs of system.hpp
// (bindings_records.hpp); its flexible bodies are Model objects kept alive by the holder.
#include "bindings/bindings_system.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings/bindings.hpp"
#include "bindings/bindings_contact.hpp"
#include "bindings/bindings_fields.hpp"
#include "bindings/bindings_model.hpp"
#include "bindings/bindings_records.hpp"
#include "fluid/fluid.hpp"
#include "solvers/system_integrator.hpp"
#include "system/sliding.hpp"
#include "system/system.hpp"
#include "system/winch.hpp"

namespace rancf_bind {

using namespace nb::literals;

namespace {

/// The contact state of a time step (all three or none): into terms.contact_*.
void step_contact(const std::optional<In>& yf, const std::optional<In>& vf,
                  const std::optional<In>& y1, std::size_t n, rancf::AssemblyTerms& terms) {
  if (!yf && !vf && !y1) return;
  if (!(yf && vf && y1))
    throw std::invalid_argument(
        "contact_yf, contact_vf and contact_y1: all three or none (a time step's contact)");
  expect_size(*yf, n, "contact_yf");
  expect_size(*vf, n, "contact_vf");
  expect_size(*y1, n, "contact_y1");
  terms.contact_yf = yf->data();
  terms.contact_vf = vf->data();
  terms.contact_y1 = y1->data();
}

struct SystemIntegratorHolder {
  rancf::SystemIntegrator integ;
  std::size_t n, m;
  SystemIntegratorHolder(const SystemHolder& h, const rancf::Scheme& sc)
      : integ(h.s, sc), n(static_cast<std::size_t>(h.s.n)), m(static_cast<std::size_t>(h.s.m)) {}
};

/// An optional float64 array field (None: none).
std::optional<In> optional_array(const Fields& p, const char* field) {
  if (p.none(field)) return std::nullopt;
  return p.array(field);
}

/// The assembly terms of TangentOptions: ck d/dy + cv d/dv + ca d/da at t, the loads times
/// load_factor (at their amplitude).
rancf::AssemblyTerms tangent_terms(const Fields& o) {
  rancf::AssemblyTerms terms;
  terms.ck = o.number("ck");
  terms.cv = o.number("cv");
  terms.ca = o.number("ca");
  terms.tf = terms.t1 = o.number("t");
  terms.load_factor = o.number("load_factor");
  terms.amplitude = o.flag("amplitude");
  return terms;
}

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

/// f(y_i, v_i, t_i, out_i) for each of the k = t.size() states (rows of y and v, n each) into
/// rows of out of `width` values, without the interpreter lock (an output worker's rows).
template <class F>
void each_row(const SystemHolder& h, const In& t, const In& y, const In& v, Out& out,
              std::size_t width, F f) {
  const std::size_t k = t.size(), n = static_cast<std::size_t>(h.s.n);
  expect_size(y, k * n, "y");
  expect_size(v, k * n, "v");
  expect_size(out, k * width, "out");
  nb::gil_scoped_release release;
  for (std::size_t i = 0; i < k; ++i)
    f(y.data() + i * n, v.data() + i * n, t.data()[i], out.data() + i * width);
}

/// Construction from one model record.
void bind_system_setup(nb::class_<SystemHolder>& cls) {
  cls.def(
         "__init__",
         [](SystemHolder* h, nb::handle model) {
           new (h) SystemHolder();
           read_model(model, *h);
         },
         "model"_a,
         "A system from one model record (rancf.kernels.records.SystemModel: its flexible "
         "bodies' Models and the records of its parts), every part at once, read by field name.")
      .def_prop_ro(
          "stiffness_damping", [](const SystemHolder& h) { return h.s.stiffness_damping; },
          "Stiffness-proportional damping beta [s] of the flexible bodies (force beta K_T v).")
      .def_prop_ro(
          "contact", [](const SystemHolder& h) { return h.contact; },
          "Its contact (rancf._core.Contact, built from the model's contact record), or None.");
}

/// The bodies of a model record alone, to evaluate places on before the joints exist.
struct PlaceFramesHolder {
  SystemHolder h;
};

void bind_place_frames(nb::module_& mod) {
  nb::class_<PlaceFramesHolder>(mod, "PlaceFrames",
                                "The places of a model's bodies at a state, before its joints.")
      .def(
          "__init__",
          [](PlaceFramesHolder* p, nb::handle model) {
            new (p) PlaceFramesHolder();
            read_places_only(model, p->h);
          },
          "model"_a,
          "From a model record's bodies (its dim, models and rigid; places and time functions "
          "are given at each call).")
      .def(
          "__call__",
          [](PlaceFramesHolder& p, nb::handle places, nb::handle time_functions, In y, double t) {
            rancf::System& s = p.h.s;
            s.places.clear();
            s.tfs.clear();
            read_records({nb::list(), places, nb::list(), nb::list(), nb::list(), time_functions,
                          nb::list(), nb::list()},
                         s);
            s.setup();
            expect_size(y, static_cast<std::size_t>(s.n), "y");
            std::vector<std::tuple<std::vector<double>, std::vector<double>>> out;
            for (const rancf::PlaceRef& pl : s.places) {
              rancf::PlaceEval e;
              rancf::place_at(s, pl, rancf::place_map(s, pl), t, y.data(), e);
              std::vector<double> fr;
              for (int k = 0; k < e.nf; ++k) fr.insert(fr.end(), e.f[k], e.f[k] + 3);
              out.emplace_back(std::vector<double>(e.x, e.x + 3), std::move(fr));
            }
            return out;
          },
          "places"_a, "time_functions"_a, "y"_a, "t"_a = 0.0,
          "(position (3), frame rows (3 k)) of each place record at (y, t) (the time functions "
          "they refer to by position): the reference frames a joint's record is measured in.");
}

/// Fluid forces, sliding joints, drums, sizes and rows.
void bind_system_drums(nb::class_<SystemHolder>& cls) {
  cls.def(
         "fluid_forces",
         [](const SystemHolder& h, In y, In v, In a, double t, bool dynamic) {
           const auto n = static_cast<std::size_t>(h.s.n);
           for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "state");
           std::vector<double> out(3 * h.s.flex.size());
           rancf::fluid_forces(h.s, y.data(), dynamic ? v.data() : nullptr,
                               dynamic ? a.data() : nullptr, t, out.data());
           return out;
         },
         "y"_a, "v"_a, "a"_a, "t"_a, "dynamic"_a = true,
         "The fluid's force (drag, inertia, buoyancy) on each flexible body, 3 values per body "
         "(world axes); dynamic = False: statics (no velocity, no inertia, no waves).")
      .def(
          "surface_elevation",
          [](const SystemHolder& h, In points, In t) {
            check(h.s.fluid != nullptr && points.size() % 3 == 0,
                  "surface_elevation: a system in a fluid and points (n, 3)");
            const std::size_t np = points.size() / 3;
            std::vector<double> out(np * t.size());
            for (std::size_t i = 0; i < t.size(); ++i)
              for (std::size_t j = 0; j < np; ++j)
                out[i * np + j] = rancf::surface_elevation(h.s.fluid->field, h.s.dim,
                                                           points.data() + 3 * j, t.data()[i]);
            return out;
          },
          "points"_a, "t"_a,
          "The free surface's height (the still surface plus the waves' elevation) above the "
          "horizontal positions of points (n, 3) at the times t: (len(t), n) row-major.")
      .def(
          "sliding_point",
          [](const SystemHolder& h, int body, In y, double sigma) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            check(h.s.sliding != nullptr && body >= 0 &&
                      static_cast<std::size_t>(body) < h.s.sliding->of_body.size() &&
                      !h.s.sliding->of_body[static_cast<std::size_t>(body)].weights.empty(),
                  "sliding_point: a body a sliding joint runs along (model.sliding)");
            rancf::SlidePoint p;
            rancf::slide_point(h.s, body, y.data(), sigma, p);
            return std::make_tuple(std::vector<double>(p.r, p.r + 3),
                                   std::vector<double>(p.rs, p.rs + 3),
                                   std::vector<double>(p.rss, p.rss + 3));
          },
          "body"_a, "y"_a, "sigma"_a,
          "(r, dr/dsigma, d2r/dsigma2) of a flexible body's centre line at the material "
          "coordinate sigma (element + parameter), 3 values each.")
      .def_prop_ro("slots", [](const SystemHolder& h) { return h.s.slots; })
      .def(
          "hold_drums",
          [](SystemHolder& h, bool hold) {
            for (const rancf::Winch& w : h.winches.winches)
              if (w.drum >= 0) h.s.fixed[static_cast<std::size_t>(w.drum)] = hold ? 1 : 0;
          },
          "hold"_a,
          "Hold the driven drums' lengths (held coordinates for the solvers built after) or "
          "free them.")
      .def_prop_ro("n", [](const SystemHolder& h) { return h.s.n; })
      .def_prop_ro("m", [](const SystemHolder& h) { return h.s.m; })
      .def_prop_ro("offsets", [](const SystemHolder& h) { return h.s.offset; })
      .def_prop_ro("joint_rows", [](const SystemHolder& h) { return h.s.joint_row; })
      .def_prop_ro("linear_row", [](const SystemHolder& h) { return h.s.linear_row; });
}

/// Constraints, the balance's residual, places and their Jacobians.
void bind_system_balance(nb::class_<SystemHolder>& cls) {
  cls.def(
         "constraints",
         [](const SystemHolder& h, In y, double t, Out g, std::optional<In> lam) {
           expect_size(y, static_cast<std::size_t>(h.s.n), "y");
           expect_size(g, static_cast<std::size_t>(h.s.m), "g");
           if (lam) expect_size(*lam, static_cast<std::size_t>(h.s.m), "lam");
           rancf::constraints(h.s, y.data(), t, g.data(), lam ? lam->data() : nullptr);
         },
         "y"_a, "t"_a, "g"_a.noconvert(), "lam"_a.none() = nb::none(),
         "Constraint residual g(y, t); lam: the multipliers, whose slots hold the sliding "
         "joints' material coordinates (needed with sliding joints).")
      .def(
          "residual",
          [](const SystemHolder& h, nb::handle point, nb::handle options) {
            const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
            const Fields p(point, "point"), o(options, "options");
            const bool dynamic = o.flag("dynamic");
            const In y = p.array("y"), lam = p.array("lam");
            expect_size(y, n, "point.y");
            expect_size(lam, m, "point.lam");
            Out r = *p.buffer("residual", n + m);
            std::optional<In> v, a;
            if (dynamic) {
              v = p.array("v");
              a = p.array("a");
              expect_size(*v, n, "point.v");
              expect_size(*a, n, "point.a");
            }
            rancf::AssemblyTerms terms;
            terms.tf = terms.t1 = o.number("t");
            terms.load_factor = o.number("load_factor");
            terms.amplitude = o.flag("amplitude");
            terms.distributed_only = o.flag("distributed_only");
            const std::optional<In> yf = optional_array(p, "contact_yf"),
                                    vf = optional_array(p, "contact_vf"),
                                    y1 = optional_array(p, "contact_y1");
            step_contact(yf, vf, y1, n, terms);  // pointers into yf, vf, y1: kept alive here
            return rancf::assemble_system(h.s, y.data(), v ? v->data() : nullptr,
                                          a ? a->data() : nullptr, lam.data(), y.data(), terms,
                                          r.data(), nullptr);
          },
          "point"_a, "options"_a,
          "The balance residual (n) and the constraints (m) at a ResidualPoint (y, lam; v, a "
          "where dynamic) into point.residual, with ResidualOptions (at t; dynamic = False: "
          "statics, no velocity or inertia terms; the loads times load_factor, at their "
          "amplitude; distributed_only: the bodies' own terms only, no point loads, loads at "
          "places or springs); point.contact_yf, contact_vf, contact_y1: the contact forces of "
          "a time step (its alpha point and end) instead of those at (y, v) "
          "(rancf.kernels.call_records).  Returns False if not finite.")
      .def(
          "place",
          [](const SystemHolder& h, int index, In y, double t) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            if (index < 0 || static_cast<std::size_t>(index) >= h.s.places.size())
              throw std::invalid_argument("place: no such place");
            const rancf::PlaceRef& p = h.s.places[static_cast<std::size_t>(index)];
            rancf::PlaceEval e;
            rancf::place_at(h.s, p, rancf::place_map(h.s, p), t, y.data(), e);
            std::vector<double> x(e.x, e.x + 3), f;
            for (int k = 0; k < e.nf; ++k) f.insert(f.end(), e.f[k], e.f[k] + 3);
            return std::make_tuple(x, f);
          },
          "index"_a, "y"_a, "t"_a,
          "(position (3), frame vectors (3 per vector, 0, 1 or 3 of them)) of a place.")
      .def(
          "place_jacobian",
          [](const SystemHolder& h, int index, In y, double t) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            if (index < 0 || static_cast<std::size_t>(index) >= h.s.places.size())
              throw std::invalid_argument("place: no such place");
            const rancf::PlaceRef& p = h.s.places[static_cast<std::size_t>(index)];
            const rancf::PlaceMap map = rancf::place_map(h.s, p);
            rancf::PlaceEval e;
            rancf::place_at(h.s, p, map, t, y.data(), e);
            std::vector<int> idx(map.index, map.index + map.n);
            std::vector<double> dx;
            for (int i = 0; i < 3; ++i) dx.insert(dx.end(), e.dx[i], e.dx[i] + map.n);
            return std::make_tuple(idx, dx);
          },
          "index"_a, "y"_a, "t"_a,
          "(global indices of the place's coordinates, d x / d local (3 x n, row-major)).");
}

/// Jacobians, joint reactions and energies.
void bind_system_outputs(nb::class_<SystemHolder>& cls) {
  cls.def(
         "dense_jacobian",
         [](const SystemHolder& h, nb::handle point, nb::handle options, Out out) {
           const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
           const Fields p(point, "point"), o(options, "options");
           const In y = p.array("y"), v = p.array("v"), a = p.array("a"), lam = p.array("lam");
           for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "point.y, v, a");
           expect_size(lam, m, "point.lam");
           expect_size(out, (n + m) * (n + m), "out");
           rancf::BorderedLU lu(h.s.offset, h.s.block_size, h.s.block_ku, h.s.fixed.data());
           std::vector<double> r(n + m);
           const rancf::AssemblyTerms terms = tangent_terms(o);
           const bool dynamic = o.flag("dynamic");
           if (!rancf::assemble_system(h.s, y.data(), dynamic ? v.data() : nullptr,
                                       dynamic ? a.data() : nullptr, lam.data(), y.data(), terms,
                                       r.data(), &lu))
             return false;
           lu.dense(h.s.m, out.data());
           return true;
         },
         "point"_a, "options"_a, "out"_a.noconvert(),
         "The Jacobian of residual() (balance and constraints) with respect to (y, lambda) at a "
         "StatePoint with TangentOptions (as sparse_jacobian), dense (n + m)^2 into out, held "
         "rows and columns as assembled.")
      .def(
          "sparse_jacobian",
          [](const SystemHolder& h, nb::handle point, nb::handle options) {
            const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
            const Fields p(point, "point"), o(options, "options");
            const In y = p.array("y"), v = p.array("v"), a = p.array("a"), lam = p.array("lam");
            for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "point.y, v, a");
            expect_size(lam, m, "point.lam");
            const rancf::AssemblyTerms terms = tangent_terms(o);
            const bool dynamic = o.flag("dynamic");
            rancf::BorderedLU lu(h.s.offset, h.s.block_size, h.s.block_ku, h.s.fixed.data());
            std::vector<double> r(n + m);
            std::vector<int> rows, cols;
            std::vector<double> vals;
            const bool ok = rancf::assemble_system(h.s, y.data(), dynamic ? v.data() : nullptr,
                                                   dynamic ? a.data() : nullptr, lam.data(),
                                                   y.data(), terms, r.data(), &lu);
            if (ok) lu.triplets(rows, cols, vals);
            return std::make_tuple(ok, h.s.n + lu.border(), rows, cols, vals);
          },
          "point"_a, "options"_a,
          "(ok, size, rows, cols, values): the Jacobian of residual() at a StatePoint (y, v, a, "
          "lam) with TangentOptions (ck d/dy + cv d/dv + ca d/da at t; dynamic = False: "
          "statics; the loads times load_factor, at their amplitude if amplitude) as the "
          "bordered solver holds it, [A P; Q D] over (y, lambda, coupling unknowns z = x_j with "
          "D = -1), held rows and columns as assembled (rancf.kernels.records).")
      .def(
          "joint_reaction",
          [](const SystemHolder& h, int k, In y, double t, In lam) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            expect_size(lam, static_cast<std::size_t>(h.s.m), "lam");
            if (k < 0 || static_cast<std::size_t>(k) >= h.s.joints.size())
              throw std::invalid_argument("joint_reaction: no such joint");
            std::array<double, 3> f{}, mo{};
            rancf::joint_reaction(h.s, k, y.data(), t, lam.data(), f.data(), mo.data());
            return std::make_tuple(f, mo);
          },
          "k"_a, "y"_a, "t"_a, "lam"_a,
          "(force, moment) joint k exerts on its first place's body (world axes).")
      .def(
          "energies",
          [](const SystemHolder& h, In y, In v, double t) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            expect_size(v, static_cast<std::size_t>(h.s.n), "v");
            double e[3];
            rancf::system_energies(h.s, y.data(), v.data(), e, t);
            return std::make_tuple(e[0], e[1], e[2]);
          },
          "y"_a, "v"_a, "t"_a = 0.0, "(kinetic, strain, gravity) energies at time t.")
      .def(
          "body_energies",
          [](const SystemHolder& h, In y, In v, double t, Out out) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            expect_size(v, static_cast<std::size_t>(h.s.n), "v");
            expect_size(out, 3 * h.s.flex.size(), "out");
            for (std::size_t b = 0; b < h.s.flex.size(); ++b)
              rancf::flex_energies(h.s, b, y.data(), v.data(), t, out.data() + 3 * b);
          },
          "y"_a, "v"_a, "t"_a, "out"_a.noconvert(),
          "Every flexible body's (kinetic, strain, gravity) energies at time t.")
      .def(
          "energies_rows",
          [](const SystemHolder& h, In t, In y, In v, Out out) {
            each_row(h, t, y, v, out, 3,
                     [&](const double* yi, const double* vi, double ti, double* oi) {
                       rancf::system_energies(h.s, yi, vi, oi, ti);
                     });
          },
          "t"_a, "y"_a, "v"_a, "out"_a.noconvert(),
          "energies of k states (rows of y, v at times t) into the rows of out (k, 3).")
      .def(
          "body_energies_rows",
          [](const SystemHolder& h, In t, In y, In v, Out out) {
            each_row(h, t, y, v, out, 3 * h.s.flex.size(),
                     [&](const double* yi, const double* vi, double ti, double* oi) {
                       for (std::size_t b = 0; b < h.s.flex.size(); ++b)
                         rancf::flex_energies(h.s, b, yi, vi, ti, oi + 3 * b);
                     });
          },
          "t"_a, "y"_a, "v"_a, "out"_a.noconvert(),
          "body_energies of k states (rows of y, v at times t) into the rows of out.");
}

/// A StaticPoint (y, lam and its residual buffer) and StaticOptions, read as both statics' entry
/// points take them.
struct StaticCall {
  In y, lam;
  Out residual;
  double load_factor, t;
  bool amplitude;
};

StaticCall read_static(const SystemIntegratorHolder& h, const Fields& p, nb::handle options) {
  const Fields o(options, "options");
  StaticCall c{
      p.array("y"),  p.array("lam"),     *p.buffer("residual", h.n + h.m), o.number("load_factor"),
      o.number("t"), o.flag("amplitude")};
  expect_size(c.y, h.n, "point.y");
  expect_size(c.lam, h.m, "point.lam");
  return c;
}

/// The statics' entry points of the system integrator: a factored residual, Newton increments.
void bind_integrator_statics(nb::class_<SystemIntegratorHolder>& cls) {
  cls.def(
         "factor_static",
         [](SystemIntegratorHolder& h, nb::handle point, nb::handle options) {
           const StaticCall c = read_static(h, Fields(point, "point"), options);
           return h.integ.factor_static(c.y.data(), c.lam.data(), c.load_factor, c.amplitude, c.t,
                                        c.residual.data(),
                                        Fields(options, "options").number("stab"));
         },
         "point"_a, "options"_a,
         "The statics' residual (balance, constraints) into point.residual at a StaticPoint (y, "
         "lam) and its Jacobian factored, with StaticOptions (load_factor, amplitude, t; stab "
         "> 0: plus stab M, the residual unchanged); False if not finite or singular.")
      .def(
          "solve_factored",
          [](SystemIntegratorHolder& h, Out x, Out z) {
            expect_size(x, h.n, "x");
            expect_size(z, h.m, "z");
            h.integ.solve_factored(x.data(), z.data());
          },
          "x"_a.noconvert(), "z"_a.noconvert(),
          "Solve with the last factorization (right-hand sides in x, z; solutions into them).")
      .def(
          "prescribe",
          [](SystemIntegratorHolder& h, double t, Out y, Out v) {
            expect_size(y, h.n, "y");
            expect_size(v, h.n, "v");
            h.integ.set_prescribed(t, y.data(), v.data(), nullptr);
          },
          "t"_a, "y"_a.noconvert(), "v"_a.noconvert(),
          "Set the moving supports' held coordinates and their rates at time t.")
      .def(
          "static_increment",
          [](SystemIntegratorHolder& h, nb::handle point, nb::handle options) {
            const Fields p(point, "point");
            const StaticCall c = read_static(h, p, options);
            Out dy = *p.buffer("dy", h.n), dlam = *p.buffer("dlam", h.m);
            return h.integ.static_increment(c.y.data(), c.lam.data(), c.load_factor, c.amplitude,
                                            c.t, dy.data(), dlam.data(), c.residual.data());
          },
          "point"_a, "options"_a,
          "One static Newton increment at a StaticPoint (K dy + G^T dlam = -r, G dy = -g into "
          "point.dy, point.dlam, point.residual) with StaticOptions; False if singular.");
}

/// The system's integrator: steps, runs, derived rows (and its statics' entry points).
void bind_system_integrator(nb::module_& mod) {
  nb::class_<SystemIntegratorHolder> cls(mod, "SystemIntegrator",
                                         "Generalized-alpha with constraints on a system.");
  cls.def(nb::init<const SystemHolder&, const rancf::Scheme&>(), "system"_a, "scheme"_a,
          nb::keep_alive<1, 2>())
      .def_prop_ro("factorizations",
                   [](const SystemIntegratorHolder& h) { return h.integ.factorizations(); })
      .def(
          "set_increment_scale",
          [](SystemIntegratorHolder& h, const std::vector<double>& scale) {
            check(scale.empty() || scale.size() == h.n, "increment scale: n values or none");
            h.integ.set_increment_scale(scale);
          },
          "scale"_a,
          "The length each coordinate's Newton increment is multiplied by in the convergence "
          "test (n values; empty: 1 for all).")
      .def(
          "set_error_tolerance",
          [](SystemIntegratorHolder& h, double tol) { h.integ.set_error_tolerance(tol); }, "tol"_a,
          "The local error a step may have (rtol times the model's size; 0: none): above it, "
          "the estimate is filtered through the iteration matrix (TI.12).")
      .def(
          "add_strain_points",
          [](SystemIntegratorHolder& h, int body, const std::vector<double>& xi,
             const std::vector<double>& n1, const std::vector<double>& n2,
             const std::vector<double>& ref, double floor, double length) {
            check(h.integ.add_strain_points(body, xi, n1, n2, ref, floor, length),
                  "strain points: a flexible body (not a beam), n1, n2 (n_el, n, 4), ref (n_el, "
                  "n), floor > 0");
          },
          "body"_a, "xi"_a, "n1"_a, "n2"_a, "ref"_a, "floor"_a, "length"_a,
          "Measure the local error in the body's axial strain too (TI.13): at the sample "
          "points, its change relative to the largest strain (at least floor), as that "
          "fraction of length.")
      .def(
          "memory", [](const SystemIntegratorHolder& h) { return h.integ.memory(); },
          "What the loop keeps between steps (see system_integrator.hpp); empty if nothing.")
      .def(
          "restore",
          [](SystemIntegratorHolder& h, const std::vector<double>& memory, long factorizations) {
            return h.integ.restore(memory, factorizations);
          },
          "memory"_a, "factorizations"_a,
          "Take up another integrator's memory() on the same system; False if it does not fit.")
      .def(
          "step",
          [](SystemIntegratorHolder& h, In y0, In v0, In a0, In w0, In l0, double t, double dt,
             Out y1, Out v1, Out a1, Out w1, Out l1) {
            for (const auto* x : {&y0, &v0, &a0, &w0}) expect_size(*x, h.n, "state");
            for (const auto* x : {&y1, &v1, &a1, &w1}) expect_size(*x, h.n, "state");
            expect_size(l0, h.m, "lambda");
            expect_size(l1, h.m, "lambda");
            rancf::StepOutcome r;
            {
              nb::gil_scoped_release release;
              r = h.integ.step({y0.data(), v0.data(), a0.data(), w0.data(), l0.data()}, t, dt,
                               {y1.data(), v1.data(), a1.data(), w1.data(), l1.data()});
            }
            return std::make_tuple(r.converged, r.iterations, r.error);
          },
          "y0"_a, "v0"_a, "a0"_a, "w0"_a, "l0"_a, "t"_a, "h"_a, "y1"_a.noconvert(),
          "v1"_a.noconvert(), "a1"_a.noconvert(), "w1"_a.noconvert(), "l1"_a.noconvert(),
          "One step from (y0, v0, a0, w0, l0) at t to t + h (w: the algorithmic accelerations); "
          "returns (converged, Newton iterations, local error estimate).")
      .def(
          "run",
          [](SystemIntegratorHolder& h, nb::handle buffers, nb::handle options) {
            const Fields o(options, "options"), b(buffers, "buffers");
            const int n_steps = o.integer("n_steps"), out_every = o.integer("out_every");
            const int done_before = o.integer("done_before");
            if (out_every < 1 || n_steps < 0 || done_before < 0)
              throw std::invalid_argument("run: bad step counts");
            Out y = *b.buffer("y", h.n), v = *b.buffer("v", h.n), a = *b.buffer("a", h.n);
            Out w = *b.buffer("w", h.n), lam = *b.buffer("lam", h.m);
            const auto n_out = static_cast<std::size_t>((done_before + n_steps) / out_every);
            Out out_y = *b.buffer("out_y", n_out * h.n), out_v = *b.buffer("out_v", n_out * h.n);
            Out out_l = *b.buffer("out_l", n_out * h.m);
            const std::optional<Out> out_e = b.buffer("out_e", n_out * 3, true);
            const std::optional<Out> out_yf = b.buffer("out_yf", n_out * h.n, true);
            const std::optional<Out> out_vf = b.buffer("out_vf", n_out * h.n, true);
            if (out_yf.has_value() != out_vf.has_value())
              throw std::invalid_argument("run: buffers.out_yf and out_vf go together");
            const double t0 = o.number("t0"), dt = o.number("h");
            const double max_seconds = o.number("max_seconds"), out_dt = o.number("out_dt");
            const std::int64_t k_last = o.integer("k_last");
            rancf::RunOutcome r;
            {
              nb::gil_scoped_release release;
              r = h.integ.run({y.data(), v.data(), a.data(), w.data(), lam.data()}, t0, dt, n_steps,
                              out_every, done_before, max_seconds, out_y.data(), out_v.data(),
                              out_l.data(), out_e ? out_e->data() : nullptr,
                              out_yf ? out_yf->data() : nullptr, out_vf ? out_vf->data() : nullptr,
                              out_dt, k_last);
            }
            return std::make_tuple(r.steps, r.converged, r.iterations, r.stored, r.max_error,
                                   r.t_max_error);
          },
          "buffers"_a, "options"_a,
          "Fixed steps with RunOptions (t0, h, n_steps, out_every, done_before, max_seconds, "
          "out_dt, k_last) on RunBuffers (the state y, v, a, w, lam updated in place; the rows "
          "stored into out_y, out_v, out_l, out_e; out_yf, out_vf: each stored row's step's "
          "alpha point, its contact forces' state) (rancf.kernels.records); returns (steps, "
          "converged, Newton iterations, outputs stored, largest local error estimate, its "
          "time).")
      .def(
          "initial_acceleration",
          [](SystemIntegratorHolder& h, In y, In v, double t, Out a, Out lam,
             std::optional<In> contact_yf, std::optional<In> contact_vf,
             std::optional<In> contact_y1) {
            for (const auto* x : {&y, &v}) expect_size(*x, h.n, "state");
            expect_size(a, h.n, "a");
            expect_size(lam, h.m, "lambda");
            rancf::AssemblyTerms contact;
            step_contact(contact_yf, contact_vf, contact_y1, h.n, contact);
            return h.integ.initial_acceleration(y.data(), v.data(), t, a.data(), lam.data(),
                                                contact.contact_yf != nullptr ? &contact : nullptr);
          },
          "y"_a, "v"_a, "t"_a, "a"_a.noconvert(), "lam"_a.noconvert(),
          "contact_yf"_a.none() = nb::none(), "contact_vf"_a.none() = nb::none(),
          "contact_y1"_a.none() = nb::none(),
          "Consistent accelerations and multipliers at (y, v, t); contact_yf, contact_vf, "
          "contact_y1: with the contact forces of a time step (its alpha point and end).")
      .def(
          "derived_rows",
          [](SystemIntegratorHolder& h, In t, In y, In v, Out a, Out lam, Out res, Out joints,
             std::size_t n_joints, std::optional<Out> res0, std::optional<Out> internal,
             std::optional<In> alpha) {
            const std::size_t k = t.size();
            for (const auto* x : {&y, &v}) expect_size(*x, k * h.n, "states");
            if (alpha) expect_size(*alpha, k * 2 * h.n, "alpha");
            expect_size(a, k * h.n, "a");
            expect_size(lam, k * h.m, "lam");
            expect_size(res, k * (h.n + h.m), "res");
            expect_size(joints, k * 6 * n_joints, "joints");
            if (res0) expect_size(*res0, k * h.n, "res0");
            if (internal) expect_size(*internal, k * h.n, "internal");
            nb::gil_scoped_release release;  // an output worker's rows beside the time loop
            h.integ.derived_rows(
                static_cast<int>(k), t.data(), y.data(), v.data(), a.data(), lam.data(), res.data(),
                joints.data(), res0 ? res0->data() : nullptr, internal ? internal->data() : nullptr,
                alpha ? alpha->data() : nullptr);
          },
          "t"_a, "y"_a, "v"_a, "a"_a.noconvert(), "lam"_a.noconvert(), "res"_a.noconvert(),
          "joints"_a.noconvert(), "n_joints"_a, "res0"_a.noconvert().none() = nb::none(),
          "internal"_a.noconvert().none() = nb::none(), "alpha"_a.none() = nb::none(),
          "Derived values of k stored states (rows of y, v at times t): the consistent a and "
          "lambda, the balance residual and constraints with them, every joint's (force, "
          "moment) (6 a joint; n_joints, the system's joints); res0: the bodies' own terms "
          "alone (distributed_only, no multipliers), internal: the element forces, n a row "
          "each, from the same assembly; alpha (k rows of 2 n, systems with contact): each "
          "row's step's alpha point (yf, vf), whose contact forces the row takes (without it "
          "the row's own state's).");
  bind_integrator_statics(cls);
}

}  // namespace

void bind_system(nb::module_& mod) {
  nb::class_<SystemHolder> cls(mod, "System", "A multibody system (see system.hpp).");
  bind_system_setup(cls);
  bind_system_drums(cls);
  bind_system_balance(cls);
  bind_system_outputs(cls);
  bind_system_integrator(mod);
  bind_place_frames(mod);
}

}  // namespace rancf_bind
