// Assembly over the element chain: forces, tangents and energy in model coordinates.
//
// Model coordinates y relate to the nodal coordinates q by q = T y, T block diagonal: identity
// except for the gradient blocks of clamped nodes, which are rotated into the basis of their
// reference tangent (rot).  Element data are gathered in q, the element kernel is called, and
// forces and tangents are mapped back (f_y = T^T f_q, K_y = T^T K_q T).
#pragma once

#include "band.hpp"
#include "model.hpp"

namespace rancf {

/// Internal force f (n) and, if k is not null, the tangent added into *k (scaled by k_scale).
void assemble(const Model& m, const double* y, double* f, const BandView* k, double k_scale);

/// Total strain energy.
double strain_energy(const Model& m, const double* y);

/// External force at time t (gravity plus point loads): f (n).
void external_force(const Model& m, double t, double* f);

}  // namespace rancf
