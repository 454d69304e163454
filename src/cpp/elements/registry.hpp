// Element kernels and their registry.
//
// A kernel computes, for element `el` with element coordinates `e` (nde values: 2 dpn for a
// line element, 4 x 12 for a shell; full nodal coordinates q: clamp rotations already undone),
// the elastic forces fe = dU/de and, when `ke` is not null, the tangent stiffness
// ke = d2U/de2 (row-major, nde x nde); and the
// strain energy U; and, if the family has Kelvin-Voigt strain-rate damping (else null), the
// damping force fe at (e, ed = de/dt) with, when `ke` is not null, its Jacobian
// ke = ck dfe/de + cv dfe/ded (not symmetric; docs/derivations/strain-rate-damping.md).
// The family also holds what the rest of the core asks of it: its section values at sample
// points, and its traits.  Code outside this registry asks kernel_for(m) and never compares
// element kinds (tests/kernels/test_element_registry.py holds that).
// A new element family is one new kernel file plus one entry in registry.cpp.
#pragma once

#include "bodies/model.hpp"

namespace rancf {

struct SamplePoints;  // bodies/sections.hpp

struct ElementKernel {
  void (*forces)(const Model& m, int el, const double* e, double* fe, double* ke);
  double (*energy)(const Model& m, int el, const double* e);
  void (*damping)(const Model& m, int el, const double* e, const double* ed, double ck, double cv,
                  double* fe, double* ke);
  /// Section values (section_width each: [eps, kappa...]) of element el with element coordinates
  /// e at the sample points p, into out (n_el, p.n, section_width) at the element's rows.
  void (*section)(const Model& m, const SamplePoints& p, int el, const double* e, double* out);
  int section_width;  ///< values per section point: 2 (cable, beam), 4 (rod) or 0 (shell)
  bool triads;        ///< nodal material frames with a twist coordinate (rods): point moments,
                      ///< rotary inertia, re-referencing, frame places
  bool centre_line;   ///< a C1 centre line with its own sample points (cables, rods; not the
                      ///< beam): strain points, sliding joints, fluid lines
  bool winch;         ///< a winch may pay it out (cables)
};

/// The kernel of the model's element family (and dimension).
const ElementKernel& kernel_for(const Model& m);

// Kernels, one file each.
extern const ElementKernel cable2d_kernel;  // cable.cpp
extern const ElementKernel cable3d_kernel;  // cable.cpp
extern const ElementKernel beam_kernel;     // beam.cpp
extern const ElementKernel rod_kernel;      // rod.cpp
extern const ElementKernel shell_kernel;    // shell.cpp

}  // namespace rancf
