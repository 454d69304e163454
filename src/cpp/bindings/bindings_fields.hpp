// Reading a record (a Python object with named fields, rancf.kernels.records) field by field:
// conversion and checks only.  A field of the wrong type, size or value raises one line that
// names it, e.g. "places[2].kind: expected one of ground, cable, ..., got 'bar'".
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings/bindings.hpp"

namespace rancf_bind {

constexpr std::size_t kAnySize = static_cast<std::size_t>(-1);

inline std::string shown(nb::handle v) {
  std::string s = nb::repr(v).c_str();
  return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

inline std::string range(const char* what, std::size_t first, std::size_t end) {
  return std::string(what) + " in [" + std::to_string(first) + ", " + std::to_string(end) + ")";
}

/// The fields of one record, named `where` in messages (e.g. "places[2]").
class Fields {
 public:
  Fields(nb::handle obj, std::string where) : obj_(obj), where_(std::move(where)) {}

  [[nodiscard]] std::string name(const char* field) const { return where_ + "." + field; }

  /// A value error naming the field.
  [[noreturn]] void fail(const char* field, const std::string& expected,
                         const std::string& got) const {
    throw std::invalid_argument(name(field) + ": expected " + expected + ", got " + got);
  }

  [[nodiscard]] int integer(const char* field) const {
    nb::object v = get(field);
    std::int64_t x = 0;
    if (PyBool_Check(v.ptr()) || !nb::try_cast(v, x)) wrong_type(field, "an integer", v);
    if (x < INT_MIN || x > INT_MAX) fail(field, "a 32-bit integer", shown(v));
    return static_cast<int>(x);
  }

  /// An index in [0, end), or -1 (none) if first is -1.
  [[nodiscard]] int index(const char* field, int first, std::size_t end, const char* what) const {
    const int i = integer(field);
    if (i < first || (i >= 0 && static_cast<std::size_t>(i) >= end))
      fail(field,
           range(what, static_cast<std::size_t>(std::max(first, 0)), end) +
               (first < 0 ? " or -1" : ""),
           std::to_string(i));
    return i;
  }

  [[nodiscard]] nb::object object(const char* field) const { return get(field); }

  [[nodiscard]] double number(const char* field) const {
    nb::object v = get(field);
    double x = 0.0;
    if (PyBool_Check(v.ptr()) || !nb::try_cast(v, x)) wrong_type(field, "a number", v);
    return x;
  }

  [[nodiscard]] bool flag(const char* field) const {
    nb::object v = get(field);
    bool x = false;
    if (!nb::try_cast(v, x)) wrong_type(field, "True or False", v);
    return x;
  }

  /// A vector of `size` numbers (kAnySize: any number of them).
  [[nodiscard]] std::vector<double> numbers(const char* field, std::size_t size) const {
    nb::object v = get(field);
    std::vector<double> x;
    if (nb::isinstance<nb::str>(v) || !nb::try_cast(v, x))
      wrong_type(field, "a sequence of numbers", v);
    if (size != kAnySize && x.size() != size)
      fail(field, std::to_string(size) + " numbers", std::to_string(x.size()));
    return x;
  }

  void numbers_into(const char* field, double* out, std::size_t size) const {
    const std::vector<double> x = numbers(field, size);
    std::copy(x.begin(), x.end(), out);
  }

  /// One of `names`, as the enum of its position.
  template <class E, std::size_t N>
  [[nodiscard]] E choice(const char* field, const std::array<const char*, N>& names) const {
    nb::object v = get(field);
    std::string allowed;
    for (const char* n : names) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
    if (!nb::isinstance<nb::str>(v)) wrong_type(field, "one of " + allowed, v);
    const std::string s = nb::cast<std::string>(v);
    for (std::size_t k = 0; k < N; ++k)
      if (s == names[k]) return static_cast<E>(k);
    fail(field, "one of " + allowed, shown(v));
  }

  /// A float64 array field (converted if need be: an input).
  [[nodiscard]] In array(const char* field) const {
    nb::object v = get(field);
    In x;
    if (!nb::try_cast(v, x)) wrong_type(field, "an array of numbers", v);
    return x;
  }

  /// A float64 C-contiguous array field written in place (never a converted copy), of `size`
  /// values; None if `optional` and the field is None.
  [[nodiscard]] std::optional<Out> buffer(const char* field, std::size_t size,
                                          bool optional = false) const {
    nb::object v = get(field);
    if (optional && v.is_none()) return std::nullopt;
    Out x;
    if (!nb::try_cast(v, x, false))
      wrong_type(field, "a C-contiguous float64 array (written in place)", v);
    if (x.size() != size) fail(field, std::to_string(size) + " values", std::to_string(x.size()));
    return x;
  }

  /// The field is None.
  [[nodiscard]] bool none(const char* field) const { return get(field).is_none(); }

 private:
  nb::handle obj_;
  std::string where_;

  [[nodiscard]] nb::object get(const char* field) const {
    if (!nb::hasattr(obj_, field))
      throw nb::type_error((name(field) + ": missing (a record with the field " + field +
                            " expected, got " + shown(obj_) + ")")
                               .c_str());
    return nb::getattr(obj_, field);
  }

  [[noreturn]] void wrong_type(const char* field, const std::string& expected, nb::handle v) const {
    throw nb::type_error((name(field) + ": expected " + expected + ", got " + shown(v)).c_str());
  }
};

/// Call f(fields) for every record of the list `list` (named `name`).
template <class F>
void each(nb::handle list, const char* name, F&& f) {
  if (!nb::isinstance<nb::sequence>(list) || nb::isinstance<nb::str>(list))
    throw nb::type_error(
        (std::string(name) + ": expected a list of records, got " + shown(list)).c_str());
  const std::size_t n = nb::len(list);
  for (std::size_t i = 0; i < n; ++i) {
    const nb::object item = list[i];
    f(Fields(item, std::string(name) + "[" + std::to_string(i) + "]"));
  }
}

}  // namespace rancf_bind
