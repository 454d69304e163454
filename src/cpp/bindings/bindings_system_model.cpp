// A system built from one model record (rancf.kernels.records.SystemModel; bindings_system.hpp):
// every part read by name, at once, in the order the core needs them.  Conversion and checks
// only.
#include <nanobind/ndarray.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings/bindings_contact.hpp"
#include "bindings/bindings_fields.hpp"
#include "bindings/bindings_model.hpp"
#include "bindings/bindings_records.hpp"
#include "bindings/bindings_system.hpp"
#include "elements/registry.hpp"

namespace rancf_bind {

namespace {

/// The flexible bodies (their Models, kept alive), time functions, dimension and rigid bodies.
void read_bodies(const Fields& f, SystemHolder& h) {
  rancf::System& s = h.s;
  s.dim = f.integer("dim");
  if (s.dim != 2 && s.dim != 3) f.fail("dim", "2 or 3", std::to_string(s.dim));
  const nb::object models = f.object("models");
  for (nb::handle m : models) {
    ModelHolder* mh = nullptr;
    if (!nb::try_cast(m, mh) || mh == nullptr)
      f.fail("models", "a sequence of rancf._core.Model", shown(m));
    h.keep.emplace_back(nb::borrow(m));
    s.flex.push_back(&mh->m);
  }
}

/// A winch's convective band matrix `field` of (2 ku + 1) n values.
std::vector<double> band(const Fields& f, const char* field, std::size_t size) {
  const In a = f.array(field);
  if (a.size() != size) f.fail(field, std::to_string(size) + " values", std::to_string(a.size()));
  return {a.data(), a.data() + size};
}

/// A driven drum of winch w (its record: the field "drum" of the winch's).
void read_drum(const Fields& f, rancf::System& s, rancf::Winch& w) {
  w.torque = f.index("torque", 0, s.tfs.size(), "a time function");
  w.mass = f.number("mass");
  w.radius = f.number("radius");
  w.rho_a = f.number("rho_a");
  if (!(w.mass > 0.0 && w.radius > 0.0 && w.rho_a >= 0.0))
    f.fail("mass", "mass, radius > 0 and rho_a >= 0", std::to_string(w.mass));
  f.numbers_into("weight", w.weight, 3);
  w.exit = f.integer("exit");
  if (w.exit < 0 || w.exit + s.dim > w.n) f.fail("exit", "a node's coordinate", "out of range");
  const In c = f.array("convective");
  w.convective.assign(c.data(), c.data() + c.size());
}

/// Winches at cable bodies' ends; a driven drum adds its coordinate after every body and drum so
/// far (its start: the winch's length_set).
void read_winches(nb::handle list, SystemHolder& h) {
  rancf::System& s = h.s;
  each(list, "model.winches", [&](const Fields& f) {
    rancf::Winch w;
    w.body = f.index("body", 0, s.flex.size(), "a flexible body");
    const rancf::Model& mod = *s.flex[static_cast<std::size_t>(w.body)];
    if (!rancf::kernel_for(mod).winch)
      f.fail("body", "a body of cable elements", std::to_string(w.body));
    w.length = f.index("length", 0, s.tfs.size(), "a time function");
    w.length_set = f.number("length_set");
    w.n = mod.n();
    w.ku = mod.ku();
    const auto size = static_cast<std::size_t>((2 * w.ku + 1) * w.n);
    w.c1 = band(f, "c1", size);
    w.c2 = band(f, "c2", size);
    w.d2 = band(f, "d2", size);
    h.winches.of_body.resize(s.flex.size(), -1);
    int& slot = h.winches.of_body[static_cast<std::size_t>(w.body)];
    if (slot >= 0) f.fail("body", "one winch per body", std::to_string(w.body));
    slot = static_cast<int>(h.winches.winches.size());
    if (!f.none("drum")) {
      read_drum(Fields(f.object("drum"), f.name("drum")), s, w);
      w.drum = s.n;  // appended after every body and drum so far
      ++h.winches.drums;
      s.winches = &h.winches;
      s.setup();
      h.y_ref.push_back(w.length_set);
    }
    h.winches.winches.push_back(std::move(w));
    s.winches = &h.winches;
  });
}

/// The element geometry of the flexible bodies sliding joints run along.
void read_sliding(nb::handle list, SystemHolder& h) {
  rancf::System& s = h.s;
  each(list, "model.sliding", [&](const Fields& f) {
    const int body = f.index("body", 0, s.flex.size(), "a flexible body");
    const rancf::Model& mod = *s.flex[static_cast<std::size_t>(body)];
    if (!rancf::kernel_for(mod).centre_line || mod.reduced())
      f.fail("body", "a body of cable or rod elements with C1 continuity", std::to_string(body));
    const auto ne = static_cast<std::size_t>(mod.n_el);
    rancf::SlidingBody b;
    b.weights = f.numbers("weights", 4 * ne);
    b.scales = f.numbers("scales", ne);
    b.closed = f.flag("closed");
    h.sliding.of_body.resize(s.flex.size());
    h.sliding.of_body[static_cast<std::size_t>(body)] = std::move(b);
    s.sliding = &h.sliding;
  });
}

/// The contact (a rancf.kernels.records.ContactRecord, one body entry per flexible body), or
/// None: the system's own rancf._core.Contact, built from it (System.contact).
void read_contact(const Fields& f, SystemHolder& h) {
  if (f.none("contact")) return;
  nb::object c = nb::type<ContactHolder>()(f.object("contact"));
  ContactHolder& ch = nb::cast<ContactHolder&>(c);
  if (ch.c.bodies.size() != h.s.flex.size())
    f.fail("contact.bodies", "one entry per flexible body", std::to_string(ch.c.bodies.size()));
  for (const rancf::Obstacle& ob : ch.c.obstacles)
    if (ob.body >= static_cast<int>(h.s.rigid.size()))
      f.fail("contact.obstacles", "obstacles on the system's rigid bodies",
             std::to_string(ob.body));
  h.s.contact = &ch.c;
  ch.sys = &h.s;
  h.contact = std::move(c);
}

/// The gravity and damping of the bodies.
void read_gravity(const Fields& f, rancf::System& s) {
  const std::vector<double> g = f.numbers("gravity", 3);
  std::copy(g.begin(), g.end(), s.gravity);
  s.damping = f.number("damping");
  s.stiffness_damping = f.number("stiffness_damping");
  if (!(s.stiffness_damping >= 0.0 && s.stiffness_damping < 1e300))
    f.fail("stiffness_damping", "a finite number >= 0", std::to_string(s.stiffness_damping));
}

/// The reference coordinates (n values, after setup).
void read_reference(const Fields& f, SystemHolder& h) {
  const rancf::System& s = h.s;
  const In y = f.array("y_ref");
  if (y.size() != static_cast<std::size_t>(s.n))
    f.fail("y_ref", std::to_string(s.n) + " values", std::to_string(y.size()));
  h.y_ref.assign(y.data(), y.data() + s.n);
}

}  // namespace

void read_places_only(nb::handle model, SystemHolder& h) {
  const Fields f(model, "model");
  read_bodies(f, h);
  read_records({f.object("rigid"), f.object("places"), nb::list(), nb::list(), nb::list(),
                f.object("time_functions"), nb::list(), nb::list()},
               h.s);
  h.s.setup();
  h.y_ref.assign(static_cast<std::size_t>(h.s.n), 0.0);
  h.s.y_ref = h.y_ref.data();
}

void read_model(nb::handle model, SystemHolder& h) {
  const Fields f(model, "model");
  read_bodies(f, h);
  read_records(
      {f.object("rigid"), f.object("places"), f.object("joints"), f.object("springs"),
       f.object("loads"), f.object("time_functions"), f.object("prescribed"), f.object("linear")},
      h.s);
  read_gravity(f, h.s);
  h.s.setup();
  read_reference(f, h);
  if (!f.none("fluid")) {
    read_fluid(f.object("fluid"), f.object("lines"), h.s, h.fluid);
    h.s.fluid = &h.fluid;
  }
  read_contact(f, h);
  read_winches(f.object("winches"), h);
  read_sliding(f.object("sliding"), h);
  check_coordinates(h.s);
  h.s.y_ref = h.y_ref.data();
}

}  // namespace rancf_bind
