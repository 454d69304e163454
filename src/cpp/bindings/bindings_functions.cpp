// Module-level functions of rancf._core: nodal triads, a band solve, Gauss-point geometry.
// Conversion and forwarding only (see bindings.cpp).
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <tuple>

#include "bindings/bindings.hpp"
#include "bodies/sections.hpp"
#include "bodies/threads.hpp"
#include "elements/cable.hpp"
#include "elements/rod.hpp"
#include "linalg/band.hpp"

namespace rancf_bind {

using namespace nb::literals;

namespace {

/// A BandLU holding the (2 ku + 1, n) C-order band storage ab.
rancf::BandLU band_from_numpy(const In& ab, std::size_t n, bool split) {
  if (n == 0 || ab.size() % n != 0 || (ab.size() / n) % 2 != 1)
    throw std::invalid_argument("ab: expected shape (2 ku + 1, n)");
  const int ni = static_cast<int>(n), ku = static_cast<int>((ab.size() / n - 1) / 2);
  rancf::BandLU lu(ni, ku);
  lu.set_split(split);
  const rancf::BandView a = lu.matrix();
  for (int j = 0; j < ni; ++j)
    for (int i = std::max(0, j - ku); i < std::min(ni, j + ku + 1); ++i)
      a.at(i, j) =
          ab.data()[static_cast<std::size_t>(ku + i - j) * n + static_cast<std::size_t>(j)];
  return lu;
}

}  // namespace

void bind_functions(nb::module_& mod) {
  mod.def(
      "set_assembly_threads",
      [](int n) {
        if (n < 1) throw std::invalid_argument("threads: expected an integer >= 1");
        rancf::set_assembly_threads(n);
      },
      "n"_a,
      "Threads the element loops of this process may use (1: none; bodies/threads.hpp); the "
      "sums are the same bit for bit whatever the number.");
  mod.def("assembly_threads", &rancf::assembly_threads,
          "Threads the element loops of this process may use.");
  mod.def(
      "min_parallel_elements", [] { return rancf::kMinParallelElements; },
      "The fewest elements a body has for its element loop to be shared between threads.");

  mod.def(
      "rod_nodal_triad",
      [](In tref, In m1ref, In rx, double phi) {
        expect_size(tref, 3, "tref");
        expect_size(m1ref, 3, "m1ref");
        expect_size(rx, 3, "rx");
        std::array<double, 3> t{}, m1{};
        rancf::rod_nodal_triad(tref.data(), m1ref.data(), rx.data(), phi, t.data(), m1.data());
        return std::make_tuple(t, m1);
      },
      "tref"_a, "m1ref"_a, "rx"_a, "phi"_a,
      "(t, m1): t = rx/|rx|, m1 = cos(phi) u + sin(phi) t x u, u = SR(tref -> t) m1ref.");

  mod.def(
      "section_forces",
      [](In raw, In kappa0, In c, double ea, bool engineering, In scale, Out out,
         std::optional<AxialLawHolder> law) {
        // raw (k, n_points, w); kappa0 (n_points, w - 1); c (w - 1); scale (k); out
        // (k, n_points, 2 w)
        const std::size_t k = scale.size(), nk = c.size(), w = nk + 1;
        if (w != 2 && w != 4) throw std::invalid_argument("c: expected 1 or 3 stiffnesses");
        const std::size_t np = k > 0 ? raw.size() / (k * w) : 0;
        expect_size(raw, k * np * w, "raw");
        expect_size(kappa0, np * nk, "kappa0");
        expect_size(out, k * np * 2 * w, "out");
        nb::gil_scoped_release release;
        rancf::section_forces(static_cast<int>(k), static_cast<int>(np), static_cast<int>(w),
                              raw.data(), kappa0.data(), c.data(), ea, engineering,
                              law_table(law ? &*law : nullptr), scale.data(), out.data());
      },
      "raw"_a, "kappa0"_a, "c"_a, "ea"_a, "engineering"_a, "scale"_a, "out"_a.noconvert(),
      "axial_law"_a = nb::none(),
      "Section values [eps, N, kappa, M] of a cable or rod from its strains and curvatures (k "
      "states; see sections.hpp).");

  mod.def(
      "tension_law",
      [](const AxialLawHolder& law, In e, Out t, Out dt, Out w) {
        const std::size_t n = e.size();
        expect_size(t, n, "t");
        expect_size(dt, n, "dt");
        expect_size(w, n, "w");
        const rancf::TensionTable f = law.table();
        for (std::size_t i = 0; i < n; ++i) {
          const rancf::LawValue v = rancf::tension_law(f, e.data()[i]);
          t.data()[i] = v.t;
          dt.data()[i] = v.dt;
          w.data()[i] = rancf::tension_law_energy(f, e.data()[i]);
        }
      },
      "law"_a, "e"_a, "t"_a.noconvert(), "dt"_a.noconvert(), "w"_a.noconvert(),
      "The law's tension T(e), slope dT/de and energy int_0^e T at the strains e (into t, dt, "
      "w; elements/tension_law.hpp).");

  mod.def(
      "band_solve",
      [](In ab, Out rhs, InB fixed, bool split) {
        // ab: (2 ku + 1, n) band storage; rhs: (n), solved in place; fixed: (n)
        expect_size(fixed, rhs.size(), "fixed");
        rancf::BandLU lu = band_from_numpy(ab, rhs.size(), split);
        if (!lu.factor(fixed.data())) return false;
        lu.solve(rhs.data(), fixed.data());
        return true;
      },
      "ab"_a, "rhs"_a.noconvert(), "fixed"_a, "split"_a = true,
      "Solve A x = rhs in place (the core's band solver: L D L^T or LU with partial pivoting, a "
      "large band split in two halves unless split=False; x[fixed] = 0); False if singular.");
  mod.def(
      "band_split_from", [](int ku) { return rancf::kSplitBands * (ku + 1); }, "ku"_a,
      "The fewest unknowns of a band of half width ku that the band solver splits in two halves.");
  mod.def(
      "band_factorization",
      [](In ab, InB fixed, bool split) -> std::string {
        rancf::BandLU lu = band_from_numpy(ab, fixed.size(), split);
        if (!lu.factor(fixed.data())) return "singular";
        return std::string(lu.split() ? "split " : "") + (lu.cholesky() ? "ldl" : "lu");
      },
      "ab"_a, "fixed"_a, "split"_a = true,
      "Which factorization band_solve takes for A: 'ldl', 'lu', 'split ldl', 'split lu' (two "
      "halves and a separator, linalg/band.hpp) or 'singular'.");

  mod.def(
      "cable_qp_geometry",
      [](In n1, In n2, In e, int dim, Out aa, Out kappa) {
        // n1, n2: (n_el, n_qp, 4); e: (n_el, 4, dim); aa, kappa: (n_el, n_qp)
        const std::size_t npts = aa.size();
        expect_size(kappa, npts, "kappa");
        expect_size(n1, npts * 4, "n1");
        expect_size(n2, npts * 4, "n2");
        if (dim != 2 && dim != 3) throw std::invalid_argument("dim: expected 2 or 3");
        const std::size_t ud = static_cast<std::size_t>(dim);
        if (npts == 0) return;
        const std::size_t n_el = e.size() / (4 * ud);
        if (n_el == 0 || npts % n_el != 0) throw std::invalid_argument("e: shape mismatch");
        const std::size_t nq = npts / n_el;
        for (std::size_t k = 0; k < npts; ++k) {
          const double* ee = e.data() + (k / nq) * 4 * ud;
          double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
          for (std::size_t i = 0; i < ud; ++i)
            for (std::size_t j = 0; j < 4; ++j) {
              a[i] += n1.data()[4 * k + j] * ee[j * ud + i];
              b[i] += n2.data()[4 * k + j] * ee[j * ud + i];
            }
          const rancf::QpGeometry g = rancf::cable_qp_geometry(a, b, dim);
          aa.data()[k] = g.aa;
          kappa.data()[k] = g.kappa;
        }
      },
      "n1"_a, "n2"_a, "e"_a, "dim"_a, "aa"_a.noconvert(), "kappa"_a.noconvert(),
      "|r'|^2 and the curvature at the Gauss points of every element (e: element coordinates).");
}

}  // namespace rancf_bind
