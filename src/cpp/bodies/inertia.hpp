// Configuration-dependent inertia: the rotary inertia of rod sections (rod_inertia.hpp; derivation
// in docs/derivations/rod-kernel.md section 11), assembled over the element chain in model
// coordinates.
//
// With it the equations of motion read
//   M_c a + c M_c v + F_in(y, v, a) + f_int(y) = f_ext(t, y),
//   F_in = M_r(y) a + g(y, v) + c M_r(y) v,
// M_c the constant mass (Model::mass_band), M_r the rotary mass matrix, g the gyroscopic
// (velocity-dependent) force and c the mass-proportional damping. F_in is zero for cables and
// beams (every function here is then a no-op), so their constant-mass path is untouched.
//
// For a time integrator: evaluate F_in where the balance puts the inertia (generalized-alpha:
// y and v at 1 - alpha_f, a at 1 - alpha_m; integrator.cpp) and pass the derivatives of those
// points with respect to the unknown as ck, cv, ca.
#pragma once

#include "bodies/model.hpp"
#include "linalg/band.hpp"

namespace rancf {

/// True if the model has configuration-dependent inertia (rods with a rotary inertia).
bool has_rotary_inertia(const Model& m);

/// Scalars of assemble_inertia: mass-proportional damping c and the Jacobian coefficients.
struct InertiaTerms {
  double damping = 0.0;  ///< c in C = c M [1/s]
  double ck = 0.0;       ///< coefficient of dF_in/dy
  double cv = 0.0;       ///< coefficient of dF_in/dv
  double ca = 0.0;       ///< coefficient of dF_in/da
};

/// r += F_in(y, v, a) (n) and, if jac is not null, jac += ck dF_in/dy + cv dF_in/dv +
/// ca dF_in/da (band, half bandwidth ku). Model coordinates; a may be null (zero acceleration).
/// The rods' nodal reference triads are those of the model (the last re-referenced state).
void assemble_inertia(const Model& m, const double* y, const double* v, const double* a,
                      const InertiaTerms& terms, double* r, const BandView* jac);

/// Rotary kinetic energy at (y, v) (0 without rotary inertia). With `current`, the nodal
/// references are taken as the current tangents (a re-referenced state, e.g. a stored output;
/// the model's triads are not read).
double rotary_kinetic_energy(const Model& m, const double* y, const double* v,
                             bool current = false);

/// Rotary angular momentum out[3] at (y, v) (zeros without rotary inertia); `current` as above.
void rotary_angular_momentum(const Model& m, const double* y, const double* v, bool current,
                             double* out);

/// Before the rods' triads are re-referenced at y: the twist rates v and accelerations a (model
/// coordinates) of nodes with a free twist are changed so that the spin and spin rate stay the
/// same under the new references (docs/derivations/rod-kernel.md 11.6). Then call rereference(m,
/// y).
void rereference_rates(const Model& m, const double* y, double* v, double* a);

}  // namespace rancf
