// The records of a system read by name into the structs of system.hpp (bindings_records.hpp):
// conversion and checks only.
#include "bindings/bindings_records.hpp"

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "bindings/bindings_fields.hpp"
#include "elements/registry.hpp"

namespace rancf_bind {

namespace {

constexpr std::array<const char*, 7> kPlaceKinds = {"ground",  "cable",   "rod", "beam",
                                                    "rigid2d", "rigid3d", "mass"};
constexpr std::array<const char*, 6> kJointKinds = {"pin",      "fixed",  "tangent",
                                                    "revolute", "slider", "sliding"};
constexpr std::array<const char*, 5> kTimeKinds = {"constant", "piecewise", "ramp", "harmonic",
                                                   "spin_up"};
bool node_kind(rancf::PlaceKind k) {
  return k == rancf::PlaceKind::cable || k == rancf::PlaceKind::rod || k == rancf::PlaceKind::beam;
}

void read_rigid(nb::handle list, rancf::System& s) {
  each(list, "rigid", [&](const Fields& f) {
    rancf::RigidInertia b;
    b.dim = f.integer("dim");
    if (b.dim != s.dim)
      f.fail("dim", std::to_string(s.dim) + " (the system's)", std::to_string(b.dim));
    b.point_mass = f.flag("point_mass");
    b.mass = f.number("mass");
    f.numbers_into("inertia", b.inertia, 3);
    s.rigid.push_back(b);
  });
}

void read_time_functions(nb::handle list, rancf::System& s) {
  each(list, "time_functions", [&](const Fields& f) {
    rancf::TimeFunction tf;
    tf.kind = f.choice<rancf::TimeKind>("kind", kTimeKinds);
    tf.value = f.numbers("value", kAnySize);
    if (tf.value.empty()) f.fail("value", "one number per component", "none");
    tf.n = static_cast<int>(tf.value.size());
    tf.duration = f.number("duration");
    tf.frequency = f.number("frequency");
    tf.phase = f.number("phase");
    tf.build_up = f.number("build_up");
    if (!(tf.build_up >= 0.0)) f.fail("build_up", "a duration >= 0", std::to_string(tf.build_up));
    tf.breaks = f.numbers("breaks", kAnySize);
    tf.coef = f.numbers("coef", kAnySize);
    if (tf.kind == rancf::TimeKind::piecewise) {
      if (tf.breaks.size() < 2)
        f.fail("breaks", "2 or more breakpoints", std::to_string(tf.breaks.size()));
      const std::size_t nc = (tf.breaks.size() - 1) * 4 * tf.value.size();
      if (tf.coef.size() != nc)
        f.fail("coef", std::to_string(nc) + " numbers (breaks - 1, 4, components)",
               std::to_string(tf.coef.size()));
    }
    s.tfs.push_back(std::move(tf));
  });
}

void read_places(nb::handle list, rancf::System& s) {
  each(list, "places", [&](const Fields& f) {
    rancf::PlaceRef p;
    p.kind = f.choice<rancf::PlaceKind>("kind", kPlaceKinds);
    if (node_kind(p.kind)) {
      p.body = f.index("body", 0, s.flex.size(), "a flexible body");
      const auto nodes =
          static_cast<std::size_t>(s.flex[static_cast<std::size_t>(p.body)]->n_nodes);
      p.node = f.index("node", 0, nodes, "a node of its body");
    } else if (p.kind != rancf::PlaceKind::ground) {
      p.body = f.index("body", 0, s.rigid.size(), "a rigid body or point mass");
      p.node = f.integer("node");
    } else {
      p.body = f.integer("body");
      p.node = f.integer("node");
    }
    f.numbers_into("point", p.point, 3);
    p.motion = f.index("motion", -1, s.tfs.size(), "a time function");
    p.rotation = f.index("rotation", -1, s.tfs.size(), "a time function");
    p.angle0 = f.number("angle0");
    s.places.push_back(p);
  });
}

void read_joints(nb::handle list, rancf::System& s) {
  const std::size_t np = s.places.size(), ntf = s.tfs.size();
  each(list, "joints", [&](const Fields& f) {
    rancf::JointData j;
    j.info.kind = f.choice<rancf::JointKind>("kind", kJointKinds);
    j.info.dim = s.dim;
    j.a = f.index("a", 0, np, "a place");
    j.b = f.index("b", 0, np, "a place");
    j.info.driven = f.flag("driven");
    j.angle = j.info.driven ? f.index("angle", 0, ntf, "a time function")
                            : f.index("angle", -1, ntf, "a time function");
    j.info.beta0 = f.number("beta0");
    const std::vector<double> rel = f.numbers("rel", 9);
    for (int k = 0; k < 9; ++k) j.info.rel[k / 3][k % 3] = rel[static_cast<std::size_t>(k)];
    f.numbers_into("axis_a", j.info.axis_a, 3);
    const std::vector<double> nb_ = f.numbers("normals_b", 6);
    for (std::size_t k = 0; k < 3; ++k) {
      j.info.normals_b[0][k] = nb_[k];
      j.info.normals_b[1][k] = nb_[3 + k];
    }
    f.numbers_into("w_a", j.info.w_a, 3);
    f.numbers_into("w_b", j.info.w_b, 3);
    j.body = j.info.kind == rancf::JointKind::sliding
                 ? f.index("body", 0, s.flex.size(), "a flexible body")
                 : f.index("body", -1, s.flex.size(), "a flexible body");
    s.joints.push_back(j);
  });
}

void read_springs(nb::handle list, rancf::System& s) {
  const std::size_t np = s.places.size();
  each(list, "springs", [&](const Fields& f) {
    rancf::SpringData d;
    d.a = f.index("a", 0, np, "a place");
    d.b = f.index("b", 0, np, "a place");
    d.stiffness = f.number("stiffness");
    d.damping = f.number("damping");
    d.length = f.number("length");
    d.law = f.index("law", -1, s.tfs.size(), "a time function");
    if (d.law >= 0) {
      const rancf::TimeFunction& law = s.tfs[static_cast<std::size_t>(d.law)];
      if (law.kind != rancf::TimeKind::piecewise || law.n != 1)
        f.fail("law", "a scalar piecewise (table) function of the stretch", std::to_string(d.law));
      if (!(d.length > 0.0))
        f.fail("length", "a rest length > 0 with a law", std::to_string(d.length));
    }
    s.springs.push_back(d);
  });
}

void read_loads(nb::handle list, rancf::System& s) {
  const std::size_t np = s.places.size(), ntf = s.tfs.size();
  each(list, "loads", [&](const Fields& f) {
    rancf::PlaceLoad l;
    l.place = f.index("place", 0, np, "a place");
    f.numbers_into("force", l.force, 3);
    f.numbers_into("torque", l.torque, 3);
    l.factor = f.index("factor", -1, ntf, "a time function");
    s.loads.push_back(l);
  });
}

void read_prescribed(nb::handle list, rancf::System& s) {
  each(list, "prescribed", [&](const Fields& f) {
    rancf::Prescribed p;
    p.coord = f.integer("coord");
    p.tf = f.index("tf", 0, s.tfs.size(), "a time function");
    const auto n = s.tfs[static_cast<std::size_t>(p.tf)].value.size();
    p.comp = f.index("comp", 0, n, "a component of its time function");
    p.base = f.number("base");
    s.prescribed.push_back(p);
  });
}

void read_linear(nb::handle list, rancf::System& s) {
  each(list, "linear", [&](const Fields& f) {
    rancf::LinearTerm t;
    t.row = f.integer("row");
    if (t.row < 0) f.fail("row", "a row >= 0", std::to_string(t.row));
    t.col = f.integer("col");
    t.coef = f.number("coef");
    s.n_linear = std::max(s.n_linear, t.row + 1);
    s.linear.push_back(t);
  });
}

}  // namespace

void read_fluid(nb::handle fluid, nb::handle lines, const rancf::System& s, rancf::FluidSet& fs) {
  const Fields f(fluid, "fluid");
  rancf::FluidField& ff = fs.field;
  ff.density = f.number("density");
  if (!(ff.density >= 0.0)) f.fail("density", "a number >= 0", std::to_string(ff.density));
  f.numbers_into("gravity", fs.gravity, 3);
  ff.has_surface = f.flag("has_surface");
  ff.surface = f.number("surface");
  f.numbers_into("current", ff.current, 3);
  ff.profile_z = f.numbers("profile_z", kAnySize);
  ff.profile_u = f.numbers("profile_u", 3 * ff.profile_z.size());
  for (std::size_t k = 1; k < ff.profile_z.size(); ++k)
    if (!(ff.profile_z[k] > ff.profile_z[k - 1]))
      f.fail("profile_z", "increasing heights", std::to_string(ff.profile_z[k]));
  rancf::Waves& w = ff.waves;
  w.on = f.flag("waves");
  w.amplitude = f.numbers("wave_amplitude", kAnySize);
  const std::size_t nw = w.amplitude.size();
  w.omega = f.numbers("wave_omega", nw);
  w.k = f.numbers("wave_k", nw);
  w.phase = f.numbers("wave_phase", nw);
  w.depth = f.number("wave_depth");
  f.numbers_into("wave_dir", w.dir, 3);
  if (w.on && !(nw > 0 && w.depth > 0.0))
    f.fail("wave_amplitude", "waves with components and depth > 0", std::to_string(nw));
  for (std::size_t i = 0; w.on && i < nw; ++i)
    if (!(w.k[i] >= 0.0 && w.omega[i] >= 0.0 && (w.k[i] > 0.0) == (w.omega[i] > 0.0)))
      f.fail("wave_k", "k, omega >= 0, both 0 or both > 0", std::to_string(w.k[i]));
  each(lines, "lines", [&](const Fields& g) {
    rancf::LineFluid ln;
    ln.body = g.index("body", 0, s.flex.size(), "a flexible body");
    const rancf::Model& m = *s.flex[static_cast<std::size_t>(ln.body)];
    if (!rancf::kernel_for(m).centre_line)
      g.fail("body", "a body of cable or rod elements", "a beam body");
    ln.hydro = g.flag("hydro");
    ln.diameter = g.number("diameter");
    ln.cdn = g.number("drag_normal");
    ln.cdt = g.number("drag_axial");
    ln.can = g.number("added_mass_normal");
    ln.cat = g.number("added_mass_axial");
    ln.n_qp = g.integer("n_qp");
    if (ln.n_qp < 1) g.fail("n_qp", "an integer >= 1", std::to_string(ln.n_qp));
    const auto nq = static_cast<std::size_t>(ln.n_qp), ne = static_cast<std::size_t>(m.n_el);
    ln.n0 = g.numbers("n0", ne * nq * 4);
    ln.n1 = g.numbers("n1", ne * nq * 4);
    ln.gw = g.numbers("gw", nq);
    ln.j0 = g.numbers("j0", ne * nq);
    each(g.object("loads"), "loads", [&](const Fields& h) {
      rancf::DistributedLoad d;
      h.numbers_into("force", d.force, 3);
      d.factor = h.index("factor", -1, s.tfs.size(), "a time function");
      ln.loads.push_back(d);
    });
    fs.lines.push_back(std::move(ln));
  });
}

void read_records(const SystemRecords& r, rancf::System& s) {
  read_rigid(r.rigid, s);
  read_time_functions(r.time_functions, s);
  read_places(r.places, s);
  read_joints(r.joints, s);
  read_springs(r.springs, s);
  read_loads(r.loads, s);
  read_prescribed(r.prescribed, s);
  read_linear(r.linear, s);
}

void check_coordinates(const rancf::System& s) {
  const auto n = static_cast<std::size_t>(s.n);
  for (std::size_t i = 0; i < s.prescribed.size(); ++i)
    if (s.prescribed[i].coord < 0 || static_cast<std::size_t>(s.prescribed[i].coord) >= n)
      throw std::invalid_argument("prescribed[" + std::to_string(i) + "].coord: expected " +
                                  range("a coordinate", 0, n) + ", got " +
                                  std::to_string(s.prescribed[i].coord));
  for (std::size_t i = 0; i < s.linear.size(); ++i)
    if (s.linear[i].col < 0 || static_cast<std::size_t>(s.linear[i].col) >= n)
      throw std::invalid_argument("linear[" + std::to_string(i) + "].col: expected " +
                                  range("a coordinate", 0, n) + ", got " +
                                  std::to_string(s.linear[i].col));
}

std::vector<double> read_vector(nb::handle v, const char* name, std::size_t size) {
  std::vector<double> x;
  if (nb::isinstance<nb::str>(v) || !nb::try_cast(v, x))
    throw nb::type_error(
        (std::string(name) + ": expected a sequence of numbers, got " + shown(v)).c_str());
  if (x.size() != size)
    throw std::invalid_argument(std::string(name) + ": expected " + std::to_string(size) +
                                " numbers, got " + std::to_string(x.size()));
  return x;
}

}  // namespace rancf_bind
