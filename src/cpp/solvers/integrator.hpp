// Generalized-alpha (Chung & Hulbert 1993, in the form of Arnold & Bruls 2007): the scheme's
// constants and Newton settings, the outcomes of steps and runs, and the energies of one body
// (the integrator of systems, which a single body is one of, is system_integrator.hpp).
//
// For M a + c M v + f_int(y) = f_ext(t), with the algorithmic accelerations w:
//   y1 = y0 + h v0 + h^2 ((1/2 - beta) w0 + beta w1),  v1 = v0 + h ((1 - gamma) w0 + gamma w1)
//   (1 - am) w1 + am w0 = (1 - af) a1 + af a0
//   M a1 + c M v1 + f_int(y1) = f_ext(t + h)
// Rods add the configuration-dependent rotary inertia F_in (inertia.hpp) at the same state:
//   F_in(y1, v1, a1) = M_r(y1) a1 + g(y1, v1) + c M_r v1,
// and after each step the twist rates are carried to the re-referenced triads (rereference_rates).
// Newton with the Jacobian [(1 - am)/((1 - af) beta h^2) + c gamma/(beta h)] M + K_T(y1)
// refreshed at every iteration (full Newton), at the first iteration of every step and reused
// for the step's further iterations while they contract (chord), or reused across iterations
// and steps until the contraction slows (modified).
#pragma once

#include <cstdint>
#include <vector>

#include "bodies/model.hpp"
#include "linalg/band.hpp"

namespace rancf {

/// Integrator constants and Newton settings.
struct Scheme {
  double alpha_m = 0.0, alpha_f = 0.0, gamma = 0.5, beta = 0.25;
  double damping = 0.0;  ///< c in C = c M [1/s]
  double tol = 1e-10;    ///< absolute tolerance on max |increment|
  int max_iter = 12;
  bool modified = false;  ///< modified Newton (reuse the factored Jacobian)
  bool chord = false;     ///< a fresh Jacobian at each step's start, reused within the step
};

struct StepOutcome {
  bool converged = false;
  int iterations = 0;
  double error = 0.0;  ///< local error estimate of a converged step (length)
};

struct RunOutcome {
  std::int64_t steps = 0;    ///< steps taken
  bool converged = true;     ///< false: the next step failed (not taken)
  long iterations = 0;       ///< Newton iterations, failed step included
  std::int64_t stored = 0;   ///< outputs stored
  double max_error = 0.0;    ///< largest local error estimate of the steps taken
  double t_max_error = 0.0;  ///< the time at the end of that step
};

/// Kinetic energy of the constant mass, 1/2 v^T M_c v.
double kinetic_energy(const Model& m, const double* v);

/// Total kinetic energy at (y, v): 1/2 v^T M_c v plus the rods' rotary part (inertia.hpp).
double kinetic_energy(const Model& m, const double* y, const double* v);

/// Gravitational potential -Q_g^T (y - y_ref) (zero in the reference configuration).
double gravity_energy(const Model& m, const double* y);

}  // namespace rancf
