// Shared pieces of the binding files: array types and size checks (conversion only).
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "elements/tension_law.hpp"

namespace rancf_bind {

namespace nb = nanobind;

using In = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;
using Out = nb::ndarray<double, nb::c_contig, nb::device::cpu>;
using InI = nb::ndarray<const std::int64_t, nb::c_contig, nb::device::cpu>;
using InB = nb::ndarray<const std::uint8_t, nb::c_contig, nb::device::cpu>;

template <class A>
void expect_size(const A& a, std::size_t size, const char* name) {
  if (a.size() != size)
    throw std::invalid_argument(std::string(name) + ": expected " + std::to_string(size) +
                                " values, got " + std::to_string(a.size()));
}

/// A tabulated tension law (elements/tension_law.hpp): breakpoints (k + 1, increasing) and cubic
/// coefficients (k, 4); checked by the constructor (bindings.cpp).
struct AxialLawHolder {
  In breaks, coef;
  [[nodiscard]] rancf::TensionTable table() const {
    return {breaks.data(), coef.data(), static_cast<int>(breaks.size()) - 1};
  }
};

/// The law's view, or none.
inline rancf::TensionTable law_table(const AxialLawHolder* law) {
  return law != nullptr ? law->table() : rancf::TensionTable{};
}

/// Module-level functions (bindings_functions.cpp).
void bind_functions(nb::module_& mod);

/// Systems (bindings_system.cpp).
void bind_system(nb::module_& mod);

/// Contact (bindings_contact.cpp).
void bind_contact(nb::module_& mod);

/// Shell elements (bindings_shell.cpp).
void bind_shell(nb::module_& mod);

}  // namespace rancf_bind
