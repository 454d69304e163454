// Contact of a system (rancf._core.Contact; bindings_contact.cpp): conversion and forwarding only.
#pragma once

#include "bindings/bindings.hpp"
#include "contact/contact.hpp"

namespace rancf_bind {

/// A system's obstacles and contact pairs; `sys` is set when a System attaches it (the System
/// keeps its Contact alive; the Python System keeps both).
struct ContactHolder {
  rancf::ContactSet c;
  const rancf::System* sys = nullptr;
};

/// Read a contact record (rancf.kernels.records.ContactRecord) into `c`, field by field: one
/// line naming the field on bad input.
void read_contact_record(nb::handle record, rancf::ContactSet& c);

}  // namespace rancf_bind
