// Generalized-alpha for constrained systems (Chung & Hulbert 1993 in the form of the one-body
// integrator, integrator.cpp; index-3 constraints as in Cardona & Geradin 1989):
//   M a_{1-am} + c M v_{1-af} + F(y_{1-af}, v_{1-af}, a_{1-am}) + G(y_{1-af})^T lambda = 0
//   g(y_{n+1}, t_{n+1}) = 0
// Newton on (y_{n+1}, lambda) with the bordered block-band matrix (bordered.hpp); lambda is the
// multiplier at the alpha point, -G^T lambda the joints' forces on the bodies.  Constraints hold
// at every step to the Newton tolerance.  With one body and no joints this is the one-body
// integrator's iteration exactly (same residual, Jacobian and convergence test).  Held
// coordinates that follow time functions (moving supports) are set at t_{n+1} before the
// iterations; their accelerations and velocities follow from the Newmark relations.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bordered.hpp"
#include "integrator.hpp"
#include "system.hpp"

namespace rancf {

class SystemIntegrator {
 public:
  SystemIntegrator(const System& s, const Scheme& scheme);
  /// One step: Newton from the predictor y0 + h v0 + h^2/2 a0; where that fails (chord: where
  /// the iteration contracts slowly), once more from y0 (the iterations of both counted).
  StepOutcome step(const double* y0, const double* v0, const double* a0, const double* l0, double t,
                   double h, double* y1, double* v1, double* a1, double* l1);
  /// Up to n_steps fixed steps from t0 (rods' triads re-referenced after each); the output
  /// interval's first done_before steps were taken by an earlier call, so y, v, lambda and the
  /// energies (kinetic, strain, gravity; none if out_e is null) go to the next rows of the
  /// outputs whenever done_before + steps taken is a multiple of out_every.  Returns after a
  /// whole step once max_seconds of wall time have passed, so the caller can poll for
  /// interrupts.
  /// out_yf, out_vf (may be null): the alpha point (y_{n+1-af}, v_{n+1-af}) of the step that
  /// ended at each stored row (before the rods' re-referencing), where its forces act.
  /// out_dt > 0: the steps' times are out_dt k + i h, k the index of the last output (k_last
  /// at the start, t0 its time) and i the steps since it, whatever steps earlier calls took
  /// (a run's numbers do not depend on where it was cut into calls); else t0 + k h.
  RunOutcome run(double* y, double* v, double* a, double* lam, double t0, double h,
                 std::int64_t n_steps, std::int64_t out_every, std::int64_t done_before,
                 double max_seconds, double* out_y, double* out_v, double* out_l, double* out_e,
                 double* out_yf = nullptr, double* out_vf = nullptr, double out_dt = 0.0,
                 std::int64_t k_last = 0);
  /// Consistent initial acceleration and multipliers: [M G^T; G 0] [a; lambda] = [-F; -c].
  /// contact (may be null): the contact forces of a step instead of those at (y, v)
  /// (AssemblyTerms::contact_yf and after), and the assembly's outputs internal and own (at
  /// the known accelerations of the held coordinates, the others zero).
  bool initial_acceleration(const double* y, const double* v, double t, double* a, double* lam,
                            const AssemblyTerms* contact = nullptr);
  /// Derived values of k stored states (rows of y and v, n each, at times t): the
  /// consistent accelerations and multipliers (initial_acceleration; zero where it fails),
  /// the balance residual and constraints with them (n + m a row) and every joint's reaction
  /// (joint_reaction: force, moment, 6 a joint): one call for a block of outputs; res0 (if not
  /// null, n a row): the bodies' own terms alone at the same a, without the multipliers
  /// (AssemblyTerms::own), and internal (if not null, n a row): the element forces
  /// (AssemblyTerms::internal), both from the pass that gives the residual, for the nodal
  /// axial forces.  Systems with contact: the contact forces are those of the step that ended
  /// at each row, alpha (if not null, 2 n a row) its generalized-alpha point (yf, vf), else the
  /// row's own state (a step of length zero).
  void derived_rows(int k, const double* t, const double* y, const double* v, double* a,
                    double* lam, double* res, double* joints, double* res0 = nullptr,
                    double* internal = nullptr, const double* alpha = nullptr);
  /// One Newton increment of the statics at load factor lf: (dy, dlam) with
  /// K dy + G^T dlam = -r, G dy = -g.  Returns false if the matrix is singular.
  bool static_increment(const double* y, const double* lam, double lf, bool amplitude, double t,
                        double* dy, double* dlam, double* residual);
  /// The statics' residual (n + m) and its Jacobian factored (for solve_factored); false if
  /// not finite or singular.
  /// stab > 0 adds stab M to the Jacobian only (not to the residual): Newton on a tangent
  /// that is singular at zero load (a pendulum's swing before its tension builds up).
  bool factor_static(const double* y, const double* lam, double lf, bool amplitude, double t,
                     double* residual, double stab = 0.0);
  /// Solve with the last factorization: x (n) and z (m) hold the right-hand side on entry.
  void solve_factored(double* x, double* z);
  [[nodiscard]] long factorizations() const { return factorizations_; }
  /// The length each coordinate's Newton increment is multiplied by in the convergence test
  /// (n values; empty: 1 for all): gradient coordinates by their elements' length, so that the
  /// test measures the displacement of the material (docs/derivations/newton.md).
  void set_increment_scale(std::vector<double> scale) { scale_ = std::move(scale); }
  /// The held coordinates that follow time functions, at time t (any pointer may be null).
  void set_prescribed(double t, double* y, double* v, double* a) const;
  /// What the loop keeps between steps: [s], the steps since one started again from y0 (0:
  /// none; step()), then, modified Newton with valid factors, the point the factored Jacobian
  /// was assembled at: [h, ck, cv, ca, tf, t1, yf (n), vf (n), am (n), y1 (n), lambda (m)].
  [[nodiscard]] std::vector<double> memory() const;
  /// Take up memory() of another integrator on the same system: the Jacobian is assembled at
  /// the same point and factored again (bit for bit the same factors); factorizations, the
  /// counter to go on from.  Memory of rancf 0.2 (without [s]: empty or the modified point
  /// alone) is taken as s = 0.  False if the data do not fit or the factorization fails.
  bool restore(const std::vector<double>& memory, long factorizations);

 private:
  /// The Newton iterations of step(), from the predictor y0 + h v0 + h^2/2 a0 or from y0.
  StepOutcome iterate(const double* y0, const double* v0, const double* a0, const double* l0,
                      double t, double h, double* y1, double* v1, double* a1, double* l1,
                      bool from_y0);
  void solve_negative();
  void remember(double h, const AssemblyTerms& terms, const double* l1, const double* y1);
  const System& s_;
  Scheme sc_;
  BorderedLU lu_;
  bool lu_valid_ = false;
  bool mass_constant_ = false;  // the matrix of initial_acceleration is M (constant): factored once
  bool mass_factored_ = false;  // lu_ holds the factors of that matrix
  double lu_h_ = -1.0;
  long factorizations_ = 0;
  std::vector<double> base_, yf_, vf_, am_, r_, dz_, zb_, zero_;
  /// Steps since one had to start again from y0 (0: the last started from the predictor and
  /// converged); below kFromY0Steps the next step starts from y0 at once, at it from the
  /// predictor.
  int from_y0_ = 0;
  static constexpr int kFromY0Steps = 8;
  std::vector<double> factored_at_;  ///< modified Newton: where the factors were assembled
  std::vector<double> scale_;        ///< set_increment_scale (empty: none)
};

/// Kinetic, strain (elements and springs) and gravitational energy of the system at (y, v)
/// (the gravity potential is zero at the system's y_ref).
void system_energies(const System& s, const double* y, const double* v, double* out,
                     double t = 0.0);

/// Kinetic, strain and gravitational energy of flexible body b at (y, v) and time t (3 values;
/// a winch's body at its length at t).
void flex_energies(const System& s, std::size_t b, const double* y, const double* v, double t,
                   double* out);

/// Re-reference the rods' nodal triads (keeping their spin rates), body by body.
void system_rereference(const System& s, double* y, double* v, double* a);

}  // namespace rancf
