// Generalized-alpha (Chung & Hulbert 1993): the scheme's constants and Newton settings, the
// outcomes of steps and runs, and the energies of one body (the integrator of systems, which a
// single body is one of, is system_integrator.hpp).
//
// For M a + c M v + f_int(y) = f_ext(t):
//   y1 = y0 + h v0 + h^2 ((1/2 - beta) a0 + beta a1),  v1 = v0 + h ((1 - gamma) a0 + gamma a1)
//   M a_{1-am} + c M v_{1-af} + f_int(y_{1-af}) = f_ext(t + (1 - af) h)
// Rods add the configuration-dependent rotary inertia F_in (inertia.hpp) at the same points:
//   F_in(y_{1-af}, v_{1-af}, a_{1-am}) = M_r(y_{1-af}) a_{1-am} + g(y_{1-af}, v_{1-af}) + c M_r v,
// and after each step the twist rates are carried to the re-referenced triads (rereference_rates).
// Newton with the Jacobian [(1 - am)/(beta h^2) + c (1 - af) gamma/(beta h)] M
// + (1 - af) K_T(y_{1-af}) refreshed at every iteration (full Newton), at the first iteration
// of every step and reused for the step's further iterations while they contract (chord), or
// reused across iterations and steps until the contraction slows (modified).
#pragma once

#include <cstdint>
#include <vector>

#include "band.hpp"
#include "model.hpp"

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
  bool converged;
  int iterations;
};

struct RunOutcome {
  std::int64_t steps;   ///< steps taken
  bool converged;       ///< false: the next step failed (not taken)
  long iterations;      ///< Newton iterations, failed step included
  std::int64_t stored;  ///< outputs stored
};

/// Kinetic energy of the constant mass, 1/2 v^T M_c v.
double kinetic_energy(const Model& m, const double* v);

/// Total kinetic energy at (y, v): 1/2 v^T M_c v plus the rods' rotary part (inertia.hpp).
double kinetic_energy(const Model& m, const double* y, const double* v);

/// Gravitational potential -Q_g^T (y - y_ref) (zero in the reference configuration).
double gravity_energy(const Model& m, const double* y);

}  // namespace rancf
