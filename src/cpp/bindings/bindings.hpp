// Shared pieces of the binding files: array types and size checks (conversion only).
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

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

/// Module-level functions (bindings_functions.cpp).
void bind_functions(nb::module_& mod);

/// Systems (bindings_system.cpp).
void bind_system(nb::module_& mod);

/// Contact (bindings_contact.cpp).
void bind_contact(nb::module_& mod);

/// Shell elements (bindings_shell.cpp).
void bind_shell(nb::module_& mod);

}  // namespace rancf_bind
