// Element kernels and their registry.
//
// A kernel computes, for element `el` with element coordinates `e` (2 dpn values, full nodal
// coordinates q: clamp rotations already undone), the elastic forces fe = dU/de and, when
// `ke` is not null, the tangent stiffness ke = d2U/de2 (row-major, 2 dpn x 2 dpn); and the
// strain energy U; and, if the family has Kelvin-Voigt strain-rate damping (else null), the
// damping force fe at (e, ed = de/dt) with, when `ke` is not null, its Jacobian
// ke = ck dfe/de + cv dfe/ded (not symmetric; docs/derivations/strain-rate-damping.md).
// A new element family is one new kernel file plus one entry in registry.cpp.
#pragma once

#include "bodies/model.hpp"

namespace rancf {

struct ElementKernel {
  void (*forces)(const Model& m, int el, const double* e, double* fe, double* ke);
  double (*energy)(const Model& m, int el, const double* e);
  void (*damping)(const Model& m, int el, const double* e, const double* ed, double ck, double cv,
                  double* fe, double* ke);
};

/// The kernel of the model's element family (and dimension).
const ElementKernel& kernel_for(const Model& m);

// Kernels, one file each.
extern const ElementKernel cable2d_kernel;  // cable.cpp
extern const ElementKernel cable3d_kernel;  // cable.cpp
extern const ElementKernel beam_kernel;     // beam.cpp
extern const ElementKernel rod_kernel;      // rod.cpp

}  // namespace rancf
