// Python bindings of systems (rancf._core.System, SystemIntegrator): conversion and forwarding
// only.  A system's parts arrive as lists of named records read into the structs of system.hpp
// (bindings_records.hpp); its flexible bodies are Model objects kept alive by the holder.
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
    throw std::invalid_argument("contact_yf, contact_vf and contact_y1 go together");
  expect_size(*yf, n, "contact_yf");
  expect_size(*vf, n, "contact_vf");
  expect_size(*y1, n, "contact_y1");
  terms.contact_yf = yf->data();
  terms.contact_vf = vf->data();
  terms.contact_y1 = y1->data();
}

struct SystemHolder {
  std::vector<nb::object> models;  // keeps the flexible bodies' arrays alive
  std::vector<double> y_ref;
  rancf::System s;
  rancf::FluidSet fluid;
  rancf::WinchSet winches;    // s.winches points here once one is attached
  rancf::SlidingSet sliding;  // s.sliding points here once a body is attached
};

struct SystemIntegratorHolder {
  rancf::SystemIntegrator integ;
  std::size_t n, m;
  SystemIntegratorHolder(const SystemHolder& h, const rancf::Scheme& sc)
      : integ(h.s, sc), n(static_cast<std::size_t>(h.s.n)), m(static_cast<std::size_t>(h.s.m)) {}
};

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

/// Construction and the parts attached to the core: contact, fluid.
void bind_system_setup(nb::class_<SystemHolder>& cls) {
  cls.def(
         "__init__",
         [](SystemHolder* h, int dim, nb::list models, nb::handle rigid, nb::handle places,
            nb::handle joints, nb::handle springs, nb::handle loads, nb::handle time_functions,
            nb::handle prescribed, nb::handle linear, nb::handle gravity, double damping,
            In y_ref) {
           new (h) SystemHolder();
           rancf::System& s = h->s;
           check(dim == 2 || dim == 3, "dim: expected 2 or 3, got " + std::to_string(dim));
           s.dim = dim;
           for (nb::handle m : models) {
             h->models.emplace_back(nb::borrow(m));
             s.flex.push_back(&nb::cast<const ModelHolder&>(m).m);
           }
           read_records({rigid, places, joints, springs, loads, time_functions, prescribed, linear},
                        s);
           const std::vector<double> g = read_vector(gravity, "gravity", 3);
           std::copy(g.begin(), g.end(), s.gravity);
           s.damping = damping;
           s.setup();
           check_coordinates(s);
           expect_size(y_ref, static_cast<std::size_t>(s.n), "y_ref");
           h->y_ref.assign(y_ref.data(), y_ref.data() + s.n);
           s.y_ref = h->y_ref.data();
         },
         nb::kw_only(), "dim"_a, "models"_a, "rigid"_a, "places"_a, "joints"_a, "springs"_a,
         "loads"_a, "time_functions"_a, "prescribed"_a, "linear"_a, "gravity"_a, "damping"_a,
         "y_ref"_a,
         "A system from its flexible bodies' Models and the lists of its records "
         "(rancf.kernels.records: rigid bodies, places, joints, springs, loads, time functions, "
         "prescribed motions, linear terms), read by field name.")
      .def_prop_rw(
          "stiffness_damping", [](const SystemHolder& h) { return h.s.stiffness_damping; },
          [](SystemHolder& h, double beta) {
            check(beta >= 0.0 && std::isfinite(beta),
                  "stiffness_damping: expected a finite number >= 0");
            h.s.stiffness_damping = beta;
          },
          "Stiffness-proportional damping beta [s] of the flexible bodies (force beta K_T v).")
      .def(
          "attach_contact",
          [](SystemHolder& h, ContactHolder& c) {
            check(c.c.bodies.size() == h.s.flex.size(), "contact: one entry per flexible body");
            h.s.contact = &c.c;
            c.sys = &h.s;
          },
          "contact"_a, nb::keep_alive<1, 2>(), "Obstacles and contact pairs (contact.hpp).")
      .def(
          "attach_fluid",
          [](SystemHolder& h, nb::handle fluid, nb::handle lines) {
            rancf::FluidSet fs;
            read_fluid(fluid, lines, h.s, fs);
            h.fluid = std::move(fs);
            h.s.fluid = &h.fluid;
          },
          "fluid"_a, "lines"_a,
          "The fluid (a FluidRecord) and the flexible bodies in it with their distributed loads "
          "(LineRecords), rancf.kernels.records (fluid.hpp).");
}

/// Fluid forces, winches, sliding joints and drums, sizes and rows.
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
          "attach_winch",
          [](SystemHolder& h, int body, int length, double length_set, In c1, In c2, In d2) {
            check(body >= 0 && static_cast<std::size_t>(body) < h.s.flex.size(),
                  "winch: body out of range");
            check(length >= 0 && static_cast<std::size_t>(length) < h.s.tfs.size(),
                  "winch: time function out of range");
            const rancf::Model& mod = *h.s.flex[static_cast<std::size_t>(body)];
            check(mod.kind == rancf::ElementKind::cable, "winch: a body of cable elements");
            rancf::Winch w;
            w.body = body;
            w.length = length;
            w.length_set = length_set;
            w.n = mod.n();
            w.ku = mod.ku();
            const std::size_t size = static_cast<std::size_t>((2 * w.ku + 1) * w.n);
            expect_size(c1, size, "c1");
            expect_size(c2, size, "c2");
            expect_size(d2, size, "d2");
            w.c1.assign(c1.data(), c1.data() + size);
            w.c2.assign(c2.data(), c2.data() + size);
            w.d2.assign(d2.data(), d2.data() + size);
            h.winches.of_body.resize(h.s.flex.size(), -1);
            check(h.winches.of_body[static_cast<std::size_t>(body)] < 0,
                  "winch: one winch per body");
            h.winches.of_body[static_cast<std::size_t>(body)] =
                static_cast<int>(h.winches.winches.size());
            h.winches.winches.push_back(std::move(w));
            h.s.winches = &h.winches;
          },
          "body"_a, "length"_a, "length_set"_a, "c1"_a, "c2"_a, "d2"_a,
          "A winch at a cable body's end (winch.hpp): time function `length` of L(t), the "
          "length the body's arrays hold, and the convective band matrices.")
      .def(
          "attach_sliding",
          [](SystemHolder& h, int body, In weights, In scales, bool closed) {
            check(body >= 0 && static_cast<std::size_t>(body) < h.s.flex.size(),
                  "sliding: body out of range");
            const rancf::Model& mod = *h.s.flex[static_cast<std::size_t>(body)];
            check(mod.kind != rancf::ElementKind::beam && !mod.reduced(),
                  "sliding: a body of cable or rod elements with C1 continuity");
            const auto ne = static_cast<std::size_t>(mod.n_el);
            expect_size(weights, 4 * ne, "weights");
            expect_size(scales, ne, "scales");
            rancf::SlidingBody b;
            b.weights.assign(weights.data(), weights.data() + 4 * ne);
            b.scales.assign(scales.data(), scales.data() + ne);
            b.closed = closed;
            h.sliding.of_body.resize(h.s.flex.size());
            h.sliding.of_body[static_cast<std::size_t>(body)] = std::move(b);
            h.s.sliding = &h.sliding;
          },
          "body"_a, "weights"_a, "scales"_a, "closed"_a,
          "The element geometry (rational weights (n_el, 4), gradient scales (n_el)) of a "
          "flexible body that sliding joints run along (sliding.hpp).")
      .def(
          "sliding_point",
          [](const SystemHolder& h, int body, In y, double sigma) {
            expect_size(y, static_cast<std::size_t>(h.s.n), "y");
            check(h.s.sliding != nullptr && body >= 0 &&
                      static_cast<std::size_t>(body) < h.s.sliding->of_body.size() &&
                      !h.s.sliding->of_body[static_cast<std::size_t>(body)].weights.empty(),
                  "sliding_point: a body attached with attach_sliding");
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
          "attach_drum",
          [](SystemHolder& h, int winch, int torque, double mass, double radius, double rho_a,
             In weight, int exit) {
            check(winch >= 0 && static_cast<std::size_t>(winch) < h.winches.winches.size(),
                  "drum: winch out of range");
            check(torque >= 0 && static_cast<std::size_t>(torque) < h.s.tfs.size(),
                  "drum: time function out of range");
            check(mass > 0.0 && radius > 0.0 && rho_a >= 0.0, "drum: mass, radius > 0");
            expect_size(weight, 3, "weight");
            rancf::Winch& w = h.winches.winches[static_cast<std::size_t>(winch)];
            check(w.drum < 0, "drum: the winch has one");
            check(exit >= 0 && exit + h.s.dim <= w.n, "drum: exit out of range");
            w.torque = torque;
            w.mass = mass;
            w.radius = radius;
            w.rho_a = rho_a;
            std::copy(weight.data(), weight.data() + 3, w.weight);
            w.exit = exit;
            w.drum = h.s.n;  // appended after every body and drum so far
            ++h.winches.drums;
            h.s.setup();
            h.y_ref.push_back(w.length_set);
            h.s.y_ref = h.y_ref.data();
            return w.drum;
          },
          "winch"_a, "torque"_a, "mass"_a, "radius"_a, "rho_a"_a, "weight"_a, "exit"_a,
          "Make winch (an index, attached before) a driven drum (winch.hpp): the time function "
          "of its torque [N m], J / r^2 [kg], r [m], the line's mass per length, its weight per "
          "length (3), the body's coordinate of the exit's position.  Adds the coordinate L "
          "(returned) after the bodies.")
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
          [](const SystemHolder& h, In y, In v, In a, In lam, double t, double load_factor,
             bool amplitude, bool dynamic, Out r, std::optional<In> contact_yf,
             std::optional<In> contact_vf, std::optional<In> contact_y1, bool distributed_only) {
            const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
            for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "state");
            expect_size(lam, m, "lam");
            expect_size(r, n + m, "r");
            rancf::AssemblyTerms terms;
            terms.tf = terms.t1 = t;
            terms.load_factor = load_factor;
            terms.amplitude = amplitude;
            terms.distributed_only = distributed_only;
            step_contact(contact_yf, contact_vf, contact_y1, n, terms);
            return rancf::assemble_system(h.s, y.data(), dynamic ? v.data() : nullptr,
                                          dynamic ? a.data() : nullptr, lam.data(), y.data(), terms,
                                          r.data(), nullptr);
          },
          "y"_a, "v"_a, "a"_a, "lam"_a, "t"_a, "load_factor"_a = 1.0, "amplitude"_a = false,
          "dynamic"_a = true, "r"_a.noconvert(), "contact_yf"_a.none() = nb::none(),
          "contact_vf"_a.none() = nb::none(), "contact_y1"_a.none() = nb::none(),
          "distributed_only"_a = false,
          "The balance residual (n) and the constraints (m) at (y, v, a, lambda, t); dynamic = "
          "False: statics (no inertia); contact_yf, contact_vf, contact_y1: the contact forces "
          "of a time step (its alpha point and end) instead of those at (y, v); "
          "distributed_only: the bodies' own terms only (no point loads, loads at places or "
          "springs).  Returns False if not finite.")
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
         [](const SystemHolder& h, In y, In v, In a, In lam, double t, double ck, double cv,
            double ca, bool dynamic, Out out) {
           const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
           for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "state");
           expect_size(lam, m, "lam");
           expect_size(out, (n + m) * (n + m), "out");
           rancf::BorderedLU lu(h.s.offset, h.s.block_size, h.s.block_ku, h.s.fixed.data());
           std::vector<double> r(n + m);
           rancf::AssemblyTerms terms;
           terms.ck = ck;
           terms.cv = cv;
           terms.ca = ca;
           terms.tf = terms.t1 = t;
           if (!rancf::assemble_system(h.s, y.data(), dynamic ? v.data() : nullptr,
                                       dynamic ? a.data() : nullptr, lam.data(), y.data(), terms,
                                       r.data(), &lu))
             return false;
           lu.dense(h.s.m, out.data());
           return true;
         },
         "y"_a, "v"_a, "a"_a, "lam"_a, "t"_a, "ck"_a, "cv"_a, "ca"_a, "dynamic"_a = true,
         "out"_a.noconvert(),
         "The Jacobian of residual() (balance and constraints) with respect to (y, lambda): ck "
         "d/dy + cv d/dv + ca d/da, dense (n + m)^2, held rows and columns as assembled.")
      .def(
          "sparse_jacobian",
          [](const SystemHolder& h, In y, In v, In a, In lam, double t, double ck, double cv,
             double ca, bool dynamic, double load_factor, bool amplitude) {
            const auto n = static_cast<std::size_t>(h.s.n), m = static_cast<std::size_t>(h.s.m);
            for (const auto* x : {&y, &v, &a}) expect_size(*x, n, "state");
            expect_size(lam, m, "lam");
            rancf::BorderedLU lu(h.s.offset, h.s.block_size, h.s.block_ku, h.s.fixed.data());
            std::vector<double> r(n + m);
            rancf::AssemblyTerms terms;
            terms.ck = ck;
            terms.cv = cv;
            terms.ca = ca;
            terms.tf = terms.t1 = t;
            terms.load_factor = load_factor;
            terms.amplitude = amplitude;
            std::vector<int> rows, cols;
            std::vector<double> vals;
            const bool ok = rancf::assemble_system(h.s, y.data(), dynamic ? v.data() : nullptr,
                                                   dynamic ? a.data() : nullptr, lam.data(),
                                                   y.data(), terms, r.data(), &lu);
            if (ok) lu.triplets(rows, cols, vals);
            return std::make_tuple(ok, h.s.n + lu.border(), rows, cols, vals);
          },
          "y"_a, "v"_a, "a"_a, "lam"_a, "t"_a, "ck"_a, "cv"_a, "ca"_a, "dynamic"_a = true,
          "load_factor"_a = 1.0, "amplitude"_a = false,
          "(ok, size, rows, cols, values): the Jacobian of residual() as the bordered solver "
          "holds it, [A P; Q D] over (y, lambda, coupling unknowns z = x_j with D = -1), held "
          "rows and columns as assembled (identity on the diagonal only after factoring: here "
          "as assembled); statics: the loads times load_factor, at their amplitude if "
          "amplitude.")
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

/// The statics' entry points of the system integrator: a factored residual, Newton increments.
void bind_integrator_statics(nb::class_<SystemIntegratorHolder>& cls) {
  cls.def(
         "factor_static",
         [](SystemIntegratorHolder& h, In y, In lam, double lf, bool amplitude, double t,
            Out residual, double stab) {
           expect_size(y, h.n, "y");
           expect_size(lam, h.m, "lam");
           expect_size(residual, h.n + h.m, "residual");
           return h.integ.factor_static(y.data(), lam.data(), lf, amplitude, t, residual.data(),
                                        stab);
         },
         "y"_a, "lam"_a, "load_factor"_a, "amplitude"_a, "t"_a, "residual"_a.noconvert(),
         "stab"_a = 0.0,
         "The statics' residual (balance, constraints) and its Jacobian factored (stab > 0: plus "
         "stab M, the residual unchanged); False if not finite or singular.")
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
          [](SystemIntegratorHolder& h, In y, In lam, double lf, bool amplitude, double t, Out dy,
             Out dlam, Out residual) {
            expect_size(y, h.n, "y");
            expect_size(dy, h.n, "dy");
            expect_size(lam, h.m, "lam");
            expect_size(dlam, h.m, "dlam");
            expect_size(residual, h.n + h.m, "residual");
            return h.integ.static_increment(y.data(), lam.data(), lf, amplitude, t, dy.data(),
                                            dlam.data(), residual.data());
          },
          "y"_a, "lam"_a, "load_factor"_a, "amplitude"_a, "t"_a, "dy"_a.noconvert(),
          "dlam"_a.noconvert(), "residual"_a.noconvert(),
          "One static Newton increment (K dy + G^T dlam = -r, G dy = -g); False if singular.");
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
          [](SystemIntegratorHolder& h, Out y, Out v, Out a, Out w, Out lam, double t0, double dt,
             std::int64_t n_steps, std::int64_t out_every, std::int64_t done_before,
             double max_seconds, Out out_y, Out out_v, Out out_l, std::optional<Out> out_e,
             std::optional<Out> out_yf, std::optional<Out> out_vf, double out_dt,
             std::int64_t k_last) {
            for (const auto* x : {&y, &v, &a, &w}) expect_size(*x, h.n, "state");
            expect_size(lam, h.m, "lambda");
            if (out_every < 1 || n_steps < 0 || done_before < 0)
              throw std::invalid_argument("run: bad step counts");
            const auto n_out = static_cast<std::size_t>((done_before + n_steps) / out_every);
            expect_size(out_y, n_out * h.n, "out_y");
            expect_size(out_v, n_out * h.n, "out_v");
            expect_size(out_l, n_out * h.m, "out_l");
            if (out_e) expect_size(*out_e, n_out * 3, "out_e");
            if (out_yf.has_value() != out_vf.has_value())
              throw std::invalid_argument("run: out_yf and out_vf go together");
            if (out_yf) {
              expect_size(*out_yf, n_out * h.n, "out_yf");
              expect_size(*out_vf, n_out * h.n, "out_vf");
            }
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
          "y"_a.noconvert(), "v"_a.noconvert(), "a"_a.noconvert(), "w"_a.noconvert(),
          "lam"_a.noconvert(), "t0"_a, "h"_a, "n_steps"_a, "out_every"_a, "done_before"_a,
          "max_seconds"_a, "out_y"_a.noconvert(), "out_v"_a.noconvert(), "out_l"_a.noconvert(),
          "out_e"_a.noconvert().none(), "out_yf"_a.noconvert().none() = nb::none(),
          "out_vf"_a.noconvert().none() = nb::none(), "out_dt"_a = 0.0, "k_last"_a = 0,
          "Fixed steps (state y, v, a, w, lam updated in place); returns (steps, converged, "
          "Newton iterations, outputs stored, largest local error estimate, its time); out_yf, "
          "out_vf: each stored row's step's alpha point (its contact forces' state).")
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
}

}  // namespace rancf_bind
