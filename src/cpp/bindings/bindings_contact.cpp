// Python bindings of contact (rancf._core.Contact): reads its named record
// (rancf.kernels.records.ContactRecord) field by field into the structs of contact.hpp, forwards.
#include "bindings/bindings_contact.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings/bindings_fields.hpp"
#include "contact/body_contact.hpp"

namespace rancf_bind {

using namespace nb::literals;

namespace {

void check(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

const rancf::System& system_of(const ContactHolder& h) {
  if (h.sys == nullptr) throw std::invalid_argument("contact: not attached to a system");
  return *h.sys;
}

const double* opt(const std::optional<In>& a, std::size_t n, const char* name) {
  if (!a) return nullptr;
  expect_size(*a, n, name);
  return a->data();
}

/// A vector field of `size` values (an array: the bodies' quadrature).
std::vector<double> values(const Fields& f, const char* field, std::size_t size) {
  const In a = f.array(field);
  if (size != kAnySize && a.size() != size)
    f.fail(field, std::to_string(size) + " values", std::to_string(a.size()));
  return {a.data(), a.data() + a.size()};
}

/// The flexible bodies' contact points and curves (ContactBodyRecord, one per flexible body).
void read_bodies(nb::handle list, rancf::ContactSet& c) {
  each(list, "contact.bodies", [&](const Fields& f) {
    rancf::ContactBody cb;
    cb.n_c = f.integer("n_c");
    if (cb.n_c < 0) f.fail("n_c", "an integer >= 0", std::to_string(cb.n_c));
    cb.radius = f.number("radius");
    cb.gw = values(f, "gw", static_cast<std::size_t>(cb.n_c));
    cb.w = values(f, "w", kAnySize);
    cb.N = values(f, "n", 4 * cb.w.size());
    cb.N1 = values(f, "n1", 4 * cb.w.size());
    cb.scales = values(f, "scales", kAnySize);
    cb.weights = values(f, "weights", 4 * cb.scales.size());
    cb.arc0 = values(f, "arc0", cb.scales.empty() ? 0 : cb.scales.size() + 1);
    c.bodies.push_back(std::move(cb));
  });
}

constexpr std::array<const char*, 3> kObstacleKinds = {"plane", "cylinder", "sphere"};

/// The obstacles (ObstacleRecord).
void read_obstacles(nb::handle list, rancf::ContactSet& c) {
  each(list, "contact.obstacles", [&](const Fields& f) {
    rancf::Obstacle ob;
    ob.kind = f.choice<rancf::ObstacleKind>("kind", kObstacleKinds);
    ob.body = f.integer("body");
    if (ob.body < -1) f.fail("body", "a rigid body's index or -1", std::to_string(ob.body));
    f.numbers_into("point", ob.point, 3);
    f.numbers_into("direction", ob.dir, 3);
    ob.radius = f.number("radius");
    c.obstacles.push_back(ob);
  });
}

/// The pairs of a flexible body and an obstacle (ContactPairRecord).
void read_pairs(nb::handle list, rancf::ContactSet& c) {
  each(list, "contact.pairs", [&](const Fields& f) {
    rancf::ContactPair cp;
    cp.flex = f.index("body", 0, c.bodies.size(), "a flexible body");
    cp.obstacle = f.index("obstacle", 0, c.obstacles.size(), "an obstacle");
    cp.stiffness = f.number("stiffness");
    cp.onset = f.number("onset");
    cp.damping = f.number("damping");
    cp.friction = f.number("friction");
    cp.slip_velocity = f.number("slip_velocity");
    cp.damping_normal = f.number("damping_normal");
    if (!(cp.stiffness > 0.0 && cp.onset > 0.0 && cp.slip_velocity > 0.0))
      f.fail("stiffness", "stiffness, onset and slip_velocity > 0", std::to_string(cp.stiffness));
    c.pairs.push_back(cp);
  });
}

/// The pairs of flexible bodies in contact (BodyPairRecord).
void read_body_pairs(nb::handle list, rancf::ContactSet& c) {
  each(list, "contact.body_pairs", [&](const Fields& f) {
    rancf::BodyPair bp;
    bp.a = f.index("a", 0, c.bodies.size(), "a flexible body");
    bp.b = f.index("b", 0, c.bodies.size(), "a flexible body");
    for (const int x : {bp.a, bp.b})
      if (c.bodies[static_cast<std::size_t>(x)].scales.empty())
        f.fail("a", "a body with contact curves (scales)", std::to_string(x));
    bp.stiffness = f.number("stiffness");
    bp.onset = f.number("onset");
    bp.friction = f.number("friction");
    bp.slip_velocity = f.number("slip_velocity");
    if (!(bp.stiffness > 0.0 && bp.onset > 0.0 && bp.friction >= 0.0 && bp.slip_velocity > 0.0))
      f.fail("stiffness", "stiffness, onset, slip_velocity > 0 and friction >= 0",
             std::to_string(bp.stiffness));
    c.body_pairs.push_back(bp);
  });
}

}  // namespace

void read_contact_record(nb::handle record, rancf::ContactSet& c) {
  const Fields f(record, "contact");
  read_bodies(f.object("bodies"), c);
  read_obstacles(f.object("obstacles"), c);
  read_pairs(f.object("pairs"), c);
  read_body_pairs(f.object("body_pairs"), c);
}

void bind_contact(nb::module_& mod) {
  mod.attr("CONTACT_OUTPUTS") = rancf::kContactOutputs;
  nb::class_<ContactHolder>(mod, "Contact", "Obstacles and contact pairs (see contact.hpp).")
      .def(
          "__init__",
          [](ContactHolder* h, nb::handle record) {
            new (h) ContactHolder();
            read_contact_record(record, h->c);
          },
          "record"_a,
          "The contact of a record (rancf.kernels.records.ContactRecord: its bodies, "
          "obstacles, pairs and body pairs), read by field name.")
      .def_prop_rw(
          "step_alpha_f", [](const ContactHolder& h) { return h.c.step_alpha_f; },
          [](ContactHolder& h, double af) {
            check(af >= 0.0 && af < 1.0, "step_alpha_f: a number in [0, 1)");
            h.c.step_alpha_f = af;
          },
          "alpha_f of the time steps whose alpha points the contact forces are given at: a "
          "point's gap of a step is the blend of its gaps at the step's ends (0: the "
          "gap at the alpha point).")
      .def(
          "body_outputs",
          [](const ContactHolder& h, In y, Out out) {
            const rancf::System& s = system_of(h);
            expect_size(y, static_cast<std::size_t>(s.n), "y");
            expect_size(out, rancf::kBodyOutputs * h.c.body_pairs.size(), "out");
            rancf::body_contact_outputs(s, h.c, y.data(), out.data());
          },
          "y"_a, "out"_a.noconvert(),
          "Per body pair: smallest gap of the candidates, points in contact, total normal force.")
      .def(
          "energy",
          [](const ContactHolder& h, In y) {
            const rancf::System& s = system_of(h);
            expect_size(y, static_cast<std::size_t>(s.n), "y");
            return rancf::contact_energy(s, h.c, y.data());
          },
          "y"_a, "The penalty's potential energy at y.")
      .def(
          "outputs",
          [](const ContactHolder& h, In y, std::optional<In> v, Out out, std::optional<In> y1) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(y, n, "y");
            expect_size(out, rancf::kContactOutputs * h.c.obstacles.size(), "out");
            rancf::contact_outputs(s, h.c, y.data(), opt(v, n, "v"), opt(y1, n, "y1"), out.data());
          },
          "y"_a, "v"_a.none(), "out"_a.noconvert(), "y1"_a.none() = nb::none(),
          "Per obstacle: normal force (3), friction force (3), moment (3), contact length, "
          "largest penetration; with y1: (y, v) a time step's alpha point, y1 its end, the "
          "forces the step applies.")
      .def(
          "points",
          [](const ContactHolder& h, int k, In y, std::optional<In> v, Out out) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(y, n, "y");
            if (k < 0 || static_cast<std::size_t>(k) >= h.c.pairs.size())
              throw std::invalid_argument("points: no such pair");
            const rancf::ContactPair& cp = h.c.pairs[static_cast<std::size_t>(k)];
            const rancf::ContactBody& cb = h.c.bodies[static_cast<std::size_t>(cp.flex)];
            expect_size(out, 8 * cb.w.size(), "out");
            rancf::contact_points(s, h.c, k, y.data(), opt(v, n, "v"), out.data());
          },
          "k"_a, "y"_a, "v"_a.none(), "out"_a.noconvert(),
          "Pair k's points: position (3), gap, pressure, friction force (3).")
      .def(
          "assemble",
          [](const ContactHolder& h, In yf, std::optional<In> vf, In y1, double ck, double cv,
             Out r, std::optional<Out> jac) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(yf, n, "yf");
            expect_size(y1, n, "y1");
            expect_size(r, n, "r");
            if (jac) expect_size(*jac, n * n, "jac");
            rancf::AssemblyTerms tm;
            tm.ck = ck;
            tm.cv = cv;
            std::fill(r.data(), r.data() + n, 0.0);
            double* dense = jac ? jac->data() : nullptr;
            if (dense != nullptr) std::fill(dense, dense + n * n, 0.0);
            const rancf::MatrixSink sink = [&](const int* idx, int k, const double* K) {
              for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b)
                  dense[static_cast<std::size_t>(idx[a]) * n + static_cast<std::size_t>(idx[b])] +=
                      K[a * k + b];
            };
            // the same state twice is one array: the pressure at yf
            const bool same = std::equal(yf.data(), yf.data() + n, y1.data());
            rancf::assemble_contact(s, h.c, yf.data(), opt(vf, n, "vf"),
                                    same ? yf.data() : y1.data(), tm, r.data(), nullptr,
                                    dense != nullptr ? &sink : nullptr);
          },
          "yf"_a, "vf"_a.none(), "y1"_a, "ck"_a, "cv"_a, "r"_a.noconvert(),
          "jac"_a.none() = nb::none(),
          "The contact terms alone (for checks): r = -(generalized contact forces) at (yf, vf) "
          "with the step's mean pressure up to y1, and their Jacobian with respect to y1, ck "
          "d/dyf + cv d/dvf + d/dy1, dense (n x n).");
}

}  // namespace rancf_bind
