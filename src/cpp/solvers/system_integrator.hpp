// Generalized-alpha for constrained systems in the form of Arnold & Bruls (2007), with index-3
// constraints as in Cardona & Geradin (1989): the balance holds at t_{n+1},
//   M a_{n+1} + c M v_{n+1} + F(y_{n+1}, v_{n+1}, a_{n+1}) + G(y_{n+1})^T lambda_{n+1} = 0,
//   g(y_{n+1}, t_{n+1}) = 0,
// and the alpha-blend acts on accelerations only, through the algorithmic accelerations w of
// the Newmark relations:
//   (1 - am) w_{n+1} + am w_n = (1 - af) a_{n+1} + af a_n,
//   y_{n+1} = y_n + h v_n + h^2 ((1/2 - beta) w_n + beta w_{n+1}),
//   v_{n+1} = v_n + h ((1 - gamma) w_n + gamma w_{n+1})
// (docs/derivations/time-integration.md).  Forces are evaluated only at real states, never at
// blends of absolute nodal coordinates (whose chords cut the circles of turning bodies).
// Newton on (y_{n+1}, lambda_{n+1}) with the bordered block-band matrix (bordered.hpp);
// -G^T lambda is the joints' force on the bodies.  Constraints hold at every step to the Newton
// tolerance.  Held coordinates that follow time functions (moving supports) are set at t_{n+1}
// before the iterations; their accelerations and velocities follow from the Newmark relations.
// Systems with contact: the contact's residual C*_{n+1} in the balance at t_{n+1} follows
// (1 - af) C*_{n+1} + af C*_n = C(yf, vf, y1), the step's mean pressure of contact.hpp at the
// alpha point, and C*_n is minus the rest of the balance's residual at the step's start:
// the other forces stay at real states, and for a constant mass matrix the contact enters as
// in the Chung-Hulbert form, whose penalty impacts do not gain energy (in the form above they
// do; docs/derivations/time-integration.md sec. 4).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "linalg/bordered.hpp"
#include "solvers/integrator.hpp"
#include "system/system.hpp"

namespace rancf {

/// The state a step starts from: coordinates y, velocities v, accelerations a (of the
/// balance), algorithmic accelerations w (of the Newmark relations) and multipliers lambda.
struct StepIn {
  const double *y, *v, *a, *w, *lam;
};

/// The state a step ends in (the same quantities, written).
struct StepOut {
  double *y, *v, *a, *w, *lam;
};

class SystemIntegrator {
 public:
  SystemIntegrator(const System& s, const Scheme& scheme);
  /// One step: Newton from the predictor y0 + h v0 + h^2/2 w0; where that fails (chord: where
  /// the iteration contracts slowly), once more from y0 (the iterations of both counted).  The
  /// outcome holds the step's local error estimate (local_error) when it converged.
  StepOutcome step(const StepIn& s0, double t, double h, const StepOut& s1);
  /// The local error of a step of length h from algorithmic accelerations w0 to w1 (n each):
  /// h^2 |beta - gamma/2 + 1/12| max_i s_i |w1_i - w0_i|, s_i the increment scale (TI.9 of
  /// docs/derivations/time-integration.md), over the coordinates that are not held.
  [[nodiscard]] double local_error(const double* w0, const double* w1, double h) const;
  /// Up to n_steps fixed steps from t0 (state x, updated in place; rods' triads re-referenced
  /// after each); the output interval's first done_before steps were taken by an earlier call,
  /// so y, v, lambda and the energies (kinetic, strain, gravity; none if out_e is null) go to
  /// the next rows of the outputs whenever done_before + steps taken is a multiple of
  /// out_every.  Returns after a whole step once max_seconds of wall time have passed, so the
  /// caller can poll for interrupts.  The outcome holds the largest local error estimate of
  /// the steps taken and the time at the end of its step.
  /// out_dt > 0: the steps' times are out_dt k + i h, k the index of the last output (k_last
  /// at the start, t0 its time) and i the steps since it, whatever steps earlier calls took
  /// (a run's numbers do not depend on where it was cut into calls); else t0 + k h.
  /// out_yf, out_vf (may be null): the alpha point (y_{n+1-af}, v_{n+1-af}) of the step that
  /// ended at each stored row (before the rods' re-referencing), where its contact forces act.
  RunOutcome run(const StepOut& x, double t0, double h, std::int64_t n_steps,
                 std::int64_t out_every, std::int64_t done_before, double max_seconds,
                 double* out_y, double* out_v, double* out_l, double* out_e,
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
  void set_increment_scale(std::vector<double> scale);
  /// The local error a step may have (rtol times the model's size; 0, the default: none).
  /// Where local_error is above it, the step's estimate is the filtered one (TI.12 of
  /// docs/derivations/time-integration.md), which leaves resolved motion alone and divides
  /// what the step does not resolve by about (omega h)^2.
  void set_error_tolerance(double tol) { error_tol_ = tol; }
  /// Measure a step's error in flexible body b's axial strain too (TI.13 of
  /// docs/derivations/time-integration.md): at sample points (sections.hpp's SamplePoints:
  /// xi, n1, n2, ref) the change of the strain that the error vector makes, relative to the
  /// largest strain there at the step's end (at least floor), counts as that fraction of
  /// length (the model's size: the displacement test's tolerance is rtol times it).
  /// False (nothing added) if b is no flexible body or a beam, or the sizes do not fit.
  bool add_strain_points(int b, std::vector<double> xi, std::vector<double> n1,
                         std::vector<double> n2, std::vector<double> ref, double floor,
                         double length);
  /// The held coordinates that follow time functions, at time t (any pointer may be null).
  void set_prescribed(double t, double* y, double* v, double* a) const;
  /// The constraints' second time derivative along y + s v + s^2/2 a_known into r_'s last m rows
  /// (right-sided at the run's start t <= 0).
  void constraint_curvature(const double* y, const double* v, const double* known,
                            const double* lam, double t);
  /// What the loop keeps between steps: [s], the steps since one started again from y0 (0:
  /// none; step()), then, modified Newton with valid factors, the point the factored Jacobian
  /// was assembled at: [h, ck, cv, ca, tf, t1, yf (n), vf (n), am (n), y1 (n), lambda (m)]
  /// (assemble_system's arguments: the balance's state and the constraints' point) and,
  /// with contact, its alpha point (y, v: 2 n).
  [[nodiscard]] std::vector<double> memory() const;
  /// Take up memory() of another integrator on the same system: the Jacobian is assembled at
  /// the same point and factored again (bit for bit the same factors); factorizations, the
  /// counter to go on from.  Memory of rancf 0.2 (without [s]: empty or the modified point
  /// alone) is taken as s = 0.  False if the data do not fit or the factorization fails.
  bool restore(const std::vector<double>& memory, long factorizations);

 private:
  /// The Newton iterations of step(), from the predictor y0 + h v0 + h^2/2 a0 or from y0.
  StepOutcome iterate(const StepIn& s0, double t, double h, const StepOut& s1, bool from_y0);
  void solve_negative();
  /// The factor on a full Newton increment dz_ (applied to it) after the step before,
  /// prev_dz_, was taken with `factor`: halved where dz_ turns back along it, else doubled
  /// up to 1 (system_integrator.cpp); w the convergence test's scale (may be null).
  double damp_reversal(double factor, const double* w);
  /// The velocities v1 of a converged step projected onto the constraints' rates at t1,
  /// G v1 + g_t = 0, in the metric of the step's iteration matrix (TI.11 of
  /// docs/derivations/time-integration.md): index-3 constraints leave the rate errors of a
  /// driven constraint undamped at rho_inf = 1.
  void project_rates(const StepOut& s1, double t1);
  /// The local error estimate filtered through the step's iteration matrix,
  /// e_f = S^-1 c_a M e, e = h^2 |beta - gamma/2 + 1/12| (w1 - w0), in the norm of
  /// local_error (TI.12); M e from two residuals of the balance at the step's end.
  double filtered_error(const StepIn& s0, const StepOut& s1, double t1, double h);
  /// The strain part of the error (add_strain_points) of the error vector e (n) at the
  /// step's end y1: max over the bodies of length |d eps|_max / max(|eps|_max, floor).
  double strain_error(const double* y1, const double* e);
  /// Modified Newton: where the factored Jacobian was assembled (assemble_system's yf, vf,
  /// am, lambda and y1).
  void remember(double h, const AssemblyTerms& terms, const double* yf, const double* vf,
                const double* am, const double* l1, const double* y1);
  const System& s_;
  Scheme sc_;
  BorderedLU lu_;
  bool lu_valid_ = false;
  bool mass_constant_ = false;  // the matrix of initial_acceleration is M (constant): factored once
  bool mass_factored_ = false;  // lu_ holds the factors of that matrix
  double lu_h_ = -1.0;
  long factorizations_ = 0;
  /// The terms of a step from t of length h (contact: at the alpha point yf_, vf_).
  [[nodiscard]] AssemblyTerms step_terms(double t, double h) const;
  /// Contact: r0_ = R_n, the balance's residual without contact at the step's start.
  bool start_residual(const StepIn& s0, double t);
  std::vector<double> base_, yf_, vf_, am_, r_, dz_, zb_, zero_, rate_g_, r0_;
  std::vector<double> prev_dz_;  // the last full Newton step taken (damp_reversal)
  /// Contact: its forces at the alpha point, carried (module comment)
  bool contact_ = false;
  /// Steps since one had to start again from y0 (0: the last started from the predictor and
  /// converged); below kFromY0Steps the next step starts from y0 at once, at it from the
  /// predictor.
  int from_y0_ = 0;
  static constexpr int kFromY0Steps = 8;
  std::vector<double> factored_at_;  ///< modified Newton: where the factors were assembled
  std::vector<double> scale_;        ///< set_increment_scale (empty: none)
  std::vector<double> error_scale_;  ///< scale_ (1 without) and 0 at the held coordinates
  double error_tol_ = 0.0;           ///< set_error_tolerance
  struct StrainPoints {              ///< add_strain_points
    int body = 0;
    std::vector<double> xi, n1, n2, ref;
    double floor = 0.0, length = 0.0;
  };
  std::vector<StrainPoints> strain_points_;
  std::vector<double> strain_y_, strain_a_, strain_b_;
};

/// Kinetic, strain (elements and springs) and gravitational energy of the system at (y, v)
/// (the gravity potential is zero at the system's y_ref).
void system_energies(const System& s, const double* y, const double* v, double* out,
                     double t = 0.0);

/// Kinetic, strain and gravitational energy of flexible body b at (y, v) and time t (3 values;
/// a winch's body at its length at t).
void flex_energies(const System& s, std::size_t b, const double* y, const double* v, double t,
                   double* out);

/// Re-reference the rods' nodal triads (keeping their spin rates), body by body; the
/// algorithmic accelerations w (may be null) are carried as the accelerations a are.
void system_rereference(const System& s, double* y, double* v, double* a, double* w = nullptr);

}  // namespace rancf
