// The records of a system (rancf.kernels.records: Python objects with named fields) read into
// the structs of system.hpp: conversion and checks only.  A field of the wrong type, size or
// value raises one line that names it, e.g.
//   places[2].kind: expected one of ground, cable, rod, beam, rigid2d, rigid3d, mass, got 'bar'
#pragma once

#include <nanobind/nanobind.h>

#include <vector>

#include "fluid/fluid.hpp"
#include "system/system.hpp"

namespace rancf_bind {

namespace nb = nanobind;

/// The lists of a system's records, read by name.
struct SystemRecords {
  nb::handle rigid, places, joints, springs, loads, time_functions, prescribed, linear;
};

/// Fill s.rigid, places, joints, springs, loads, tfs, prescribed, linear and n_linear from the
/// records (s.dim and s.flex set); indices between the lists and into the bodies are checked.
void read_records(const SystemRecords& r, rancf::System& s);

/// Fill fs from a FluidRecord and a list of LineRecords (rancf.kernels.records), their bodies'
/// element and quadrature counts and time functions checked against s.
void read_fluid(nb::handle fluid, nb::handle lines, const rancf::System& s, rancf::FluidSet& fs);

/// After s.setup(): the coordinates of the prescribed motions and linear terms exist.
void check_coordinates(const rancf::System& s);

/// A vector of exactly `size` numbers (gravity), or one line naming `name`.
std::vector<double> read_vector(nb::handle v, const char* name, std::size_t size);

}  // namespace rancf_bind
