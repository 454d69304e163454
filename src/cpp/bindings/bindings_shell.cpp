// Python bindings of the shell elements (rancf._core.ShellKernel; elements/shell.hpp): one
// ShellRecord (rancf.kernels.records) read by field name, conversion and forwarding only.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/tuple.h>

#include <array>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings/bindings.hpp"
#include "bindings/bindings_fields.hpp"
#include "elements/shell.hpp"

namespace rancf_bind {

using namespace nb::literals;

namespace {

template <class T>
using Vec = nb::ndarray<nb::numpy, T, nb::ndim<1>>;

/// A NumPy array that owns the vector's memory.
template <class T>
Vec<T> to_numpy(std::vector<T>&& v) {
  auto* p = new std::vector<T>(std::move(v));
  nb::capsule owner(p, [](void* x) noexcept { delete static_cast<std::vector<T>*>(x); });
  return Vec<T>(p->data(), {p->size()}, owner);
}

/// `size` numbers of a float array field (any shape, C order).
std::vector<double> field_values(const Fields& f, const char* field, std::size_t size) {
  const In a = f.array(field);
  if (size != kAnySize && a.size() != size)
    f.fail(field, std::to_string(size) + " values", std::to_string(a.size()));
  return {a.data(), a.data() + a.size()};
}

rancf::ShellInput read_shell(nb::handle record) {
  const Fields f(record, "shell");
  rancf::ShellInput in;
  InI conn;
  const nb::object c = f.object("connectivity");
  const bool integer =
      nb::hasattr(c, "dtype") && std::string(nb::str(c.attr("dtype").attr("kind")).c_str()) == "i";
  if (!integer || !nb::try_cast(c, conn))
    f.fail("connectivity", "an array of integers (n_el, 4)", shown(c));
  if (conn.size() == 0 || conn.size() % 4 != 0)
    f.fail("connectivity", "(n_el, 4) node indices, n_el >= 1", std::to_string(conn.size()));
  in.connectivity.assign(conn.data(), conn.data() + conn.size());
  const std::size_t ne = conn.size() / 4;
  in.weights_u = field_values(f, "weights_u", 4 * ne);
  in.weights_v = field_values(f, "weights_v", 4 * ne);
  in.scales = field_values(f, "scales", 2 * ne);
  in.q0 = field_values(f, "q0", kAnySize);
  if (in.q0.empty() || in.q0.size() % 12 != 0)
    f.fail("q0", "12 coordinates a node", std::to_string(in.q0.size()));
  in.n_nodes = static_cast<int>(in.q0.size() / 12);
  in.material = {f.number("thickness"), f.number("youngs_modulus"), f.number("poisson_ratio"),
                 f.number("density")};
  in.gauss = f.integer("gauss");
  in.membrane = f.choice<rancf::MembraneStrains>(
      "membrane", std::array<const char*, 3>{"full", "projected", "reduced"});
  return in;
}

void expect_q(const rancf::ShellElements& s, const In& q) {
  expect_size(q, static_cast<std::size_t>(s.n()), "q");
}

auto triplets(rancf::Triplets&& t) {
  return std::make_tuple(to_numpy(std::move(t.rows)), to_numpy(std::move(t.cols)),
                         to_numpy(std::move(t.values)));
}

}  // namespace

void bind_shell(nb::module_& mod) {
  nb::class_<rancf::ShellElements>(mod, "ShellKernel",
                                   "Kirchhoff-Love RANCF shell elements of one ShellRecord "
                                   "(elements/shell.hpp; docs/derivations/shell.md sec. 3-6).")
      .def(
          "__init__",
          [](rancf::ShellElements* s, nb::handle record) {
            new (s) rancf::ShellElements(read_shell(record));
          },
          "record"_a)
      .def_prop_ro("n", &rancf::ShellElements::n, "Number of coordinates (12 a node).")
      .def_prop_ro("n_el", &rancf::ShellElements::n_el, "Number of elements.")
      .def(
          "energy",
          [](const rancf::ShellElements& s, In q) {
            expect_q(s, q);
            return s.energy(q.data());
          },
          "q"_a, "Strain energy W(q) (eq. 4.7).")
      .def(
          "forces",
          [](const rancf::ShellElements& s, In q) {
            expect_q(s, q);
            std::vector<double> f(static_cast<std::size_t>(s.n()));
            s.forces(q.data(), f.data());
            return to_numpy(std::move(f));
          },
          "q"_a, "Internal forces dW/dq (eq. 4.8).")
      .def(
          "tangent",
          [](const rancf::ShellElements& s, In q) {
            expect_q(s, q);
            return triplets(s.tangent(q.data()));
          },
          "q"_a, "Tangent d2W/dq2 (eq. 4.9) as (rows, cols, values), duplicates to be summed.")
      .def(
          "mass", [](const rancf::ShellElements& s) { return triplets(s.mass()); },
          "Consistent mass matrix (sec. 6) as (rows, cols, values), duplicates to be summed.")
      .def(
          "area_load",
          [](const rancf::ShellElements& s, In p) {
            expect_size(p, 3, "p");
            std::vector<double> f(static_cast<std::size_t>(s.n()));
            s.area_load(p.data(), f.data());
            return to_numpy(std::move(f));
          },
          "p"_a, "Consistent nodal forces of a constant force p (3) per reference area (sec. 6).")
      .def(
          "pressure",
          [](const rancf::ShellElements& s, In q, double p) {
            expect_q(s, q);
            std::vector<double> f(static_cast<std::size_t>(s.n()));
            s.pressure(q.data(), p, f.data(), nullptr);
            return to_numpy(std::move(f));
          },
          "q"_a, "p"_a, "Forces of a follower pressure p along the current normal a3 (sec. 6).")
      .def(
          "pressure_tangent",
          [](const rancf::ShellElements& s, In q, double p) {
            expect_q(s, q);
            std::vector<double> f(static_cast<std::size_t>(s.n()));
            rancf::Triplets t;
            s.pressure(q.data(), p, f.data(), &t);
            return triplets(std::move(t));
          },
          "q"_a, "p"_a,
          "d/dq of the pressure forces (not symmetric) as (rows, cols, values), duplicates to be "
          "summed.");
}

}  // namespace rancf_bind
