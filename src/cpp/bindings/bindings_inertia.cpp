// Methods of rancf._core.Model for the configuration-dependent (rotary) inertia of rods
// (inertia.hpp). Conversion and forwarding only (see bindings.cpp).
#include <nanobind/stl/array.h>

#include <algorithm>
#include <array>

#include "bindings/bindings_model.hpp"
#include "bodies/inertia.hpp"
#include "linalg/band.hpp"

namespace rancf_bind {

using namespace nb::literals;

void bind_inertia(nb::class_<ModelHolder>& cls) {
  cls.def(
      "inertia",
      [](const ModelHolder& h, In y, In v, In a, double damping, double ck, double cv, double ca,
         Out f, Out ab) {
        for (const auto* x : {&y, &v, &a}) expect_size(*x, h.n(), "state");
        expect_size(f, h.n(), "f");
        expect_size(ab, h.band_size(), "ab");
        std::fill(f.data(), f.data() + f.size(), 0.0);
        std::fill(ab.data(), ab.data() + ab.size(), 0.0);
        const rancf::BandView k = rancf::numpy_band(ab.data(), h.m.n(), h.m.ku());
        rancf::assemble_inertia(h.m, y.data(), v.data(), a.data(), {damping, ck, cv, ca}, f.data(),
                                &k);
      },
      "y"_a, "v"_a, "a"_a, "damping"_a, "ck"_a, "cv"_a, "ca"_a, "f"_a.noconvert(),
      "ab"_a.noconvert(),
      "Rotary inertial force F_in(y, v, a) (written into f) and ck dF/dy + cv dF/dv + ca dF/da in "
      "(2 ku + 1, n) band storage (zero for cables and beams).");
  cls.def(
      "rotary_kinetic_energy",
      [](const ModelHolder& h, In y, In v, bool current) {
        for (const auto* x : {&y, &v}) expect_size(*x, h.n(), "state");
        return rancf::rotary_kinetic_energy(h.m, y.data(), v.data(), current);
      },
      "y"_a, "v"_a, "current"_a = false,
      "Rotary kinetic energy (current: the nodal references are the current tangents).");
  cls.def(
      "rotary_angular_momentum",
      [](const ModelHolder& h, In y, In v, bool current) {
        for (const auto* x : {&y, &v}) expect_size(*x, h.n(), "state");
        std::array<double, 3> out{};
        rancf::rotary_angular_momentum(h.m, y.data(), v.data(), current, out.data());
        return out;
      },
      "y"_a, "v"_a, "current"_a = false,
      "Rotary angular momentum (3) (current: the nodal references are the current tangents).");
}

}  // namespace rancf_bind
