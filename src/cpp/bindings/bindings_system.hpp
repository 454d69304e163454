// A system as the binding holds it (rancf._core.System; bindings_system.cpp) and its construction
// from one model record (rancf.kernels.records.SystemModel; bindings_system_model.cpp).
#pragma once

#include <nanobind/nanobind.h>

#include <vector>

#include "fluid/fluid.hpp"
#include "system/sliding.hpp"
#include "system/system.hpp"
#include "system/winch.hpp"

namespace rancf_bind {

namespace nb = nanobind;

/// The core's System and what it points into: the flexible bodies' Models and the Contact (kept
/// alive), the reference coordinates, fluid, winches and sliding joints' bodies.
struct SystemHolder {
  std::vector<nb::object> keep;     // the flexible bodies' Models
  nb::object contact = nb::none();  // its rancf._core.Contact (None: no contact)
  std::vector<double> y_ref;
  rancf::System s;
  rancf::FluidSet fluid;
  rancf::WinchSet winches;    // s.winches points here if the model has winches
  rancf::SlidingSet sliding;  // s.sliding points here if the model has sliding bodies
};

/// Build h (constructed empty) from a model record, every part at once: bodies, places, joints,
/// springs, loads, time functions, prescribed motions, linear rows, fluid, contact, winches and
/// their drums, sliding bodies.  One line naming the field on bad input.
void read_model(nb::handle model, SystemHolder& h);

/// The bodies, time functions and places of a model record only (no joints or other parts),
/// set up: for evaluating places before the joints' reference data exist.
void read_places_only(nb::handle model, SystemHolder& h);

}  // namespace rancf_bind
