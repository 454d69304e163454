// Generalized-alpha time stepping (Chung & Hulbert 1993).
//
// For M a + c M v + f_int(y) = f_ext(t):
//   y1 = y0 + h v0 + h^2 ((1/2 - beta) a0 + beta a1),  v1 = v0 + h ((1 - gamma) a0 + gamma a1)
//   M a_{1-am} + c M v_{1-af} + f_int(y_{1-af}) = f_ext(t + (1 - af) h)
// Rods add the configuration-dependent rotary inertia F_in (inertia.hpp) at the same points:
//   F_in(y_{1-af}, v_{1-af}, a_{1-am}) = M_r(y_{1-af}) a_{1-am} + g(y_{1-af}, v_{1-af}) + c M_r v,
// and after each step the twist rates are carried to the re-referenced triads (rereference_rates).
// Newton on y1 with the Jacobian [(1 - am)/(beta h^2) + c (1 - af) gamma/(beta h)] M
// + (1 - af) K_T(y_{1-af}); the band LU (partial pivoting) is refreshed at every iteration
// (full Newton) or reused across iterations and steps until the contraction slows (modified).
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

class Integrator {
 public:
  Integrator(const Model& m, const Scheme& s);
  /// One step of size h from (y0, v0, a0) at time t into (y1, v1, a1).
  StepOutcome step(const double* y0, const double* v0, const double* a0, double t, double h,
                   double* y1, double* v1, double* a1);
  /// Up to n_steps fixed steps from time t0 (rod triads re-referenced after each), y, v, a
  /// updated in place; the first output interval already holds done_before steps, and every
  /// out_every steps of an interval the state and the energies (kinetic, strain, gravity) go to
  /// the next rows of out_y, out_v, out_e.  Returns early, after a whole step, once max_seconds
  /// of wall time have passed (the caller polls for interrupts between calls).
  RunOutcome run(double* y, double* v, double* a, double t0, double h, std::int64_t n_steps,
                 std::int64_t out_every, std::int64_t done_before, double max_seconds,
                 double* out_y, double* out_v, double* out_e);
  /// a = M^-1 (f_ext(t) - f_int(y) - c M v).
  void initial_acceleration(const double* y, const double* v, double t, double* a);
  [[nodiscard]] long factorizations() const { return factorizations_; }

 private:
  const Model& m_;
  Scheme s_;
  BandLU lu_;
  bool lu_valid_ = false;
  double lu_h_ = -1.0;
  long factorizations_ = 0;
  std::vector<double> base_, fext_, yf_, fi_, tmp_, mv_;
  std::vector<double> vf_, aam_;  // rods: v at 1 - alpha_f, a at 1 - alpha_m (rotary inertia)
};

/// Kinetic energy of the constant mass, 1/2 v^T M_c v.
double kinetic_energy(const Model& m, const double* v);

/// Total kinetic energy at (y, v): 1/2 v^T M_c v plus the rods' rotary part (inertia.hpp).
double kinetic_energy(const Model& m, const double* y, const double* v);

/// Gravitational potential -Q_g^T (y - y_ref) (zero in the reference configuration).
double gravity_energy(const Model& m, const double* y);

}  // namespace rancf
