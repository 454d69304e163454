// Winches: cables whose material flows through the mesh at one end (docs/derivations/
// variable-length.md §2).
//
// The unstretched length outside the winch is L(t) (a time function); the body's arrays (the
// reference metric s0, J0, the stress-free curvature, mass band, gravity forces) hold the length
// `length_set`, and the balance at time t uses them stretched by ratio = L(t) / length_set
// (a scaled copy of the model, no change to the element kernels), plus the convective inertia of
// the material moving through the mesh:
//   2 L' C1 v + [(L'' - 2 L'^2 / L) C1 + (L'^2 / L) C2] y,
// and the kinetic energy 1/2 ratio v^T M v + L' v^T C1 y + 1/2 (L'^2 / L) y^T D2 y, with the
// constant band matrices C1, C2, D2 computed once by rancf.bodies.winch_inertia.
//
// A driven drum (docs/derivations/variable-length.md §3) makes L a coordinate of the system,
// y[drum], with its own balance: Lagrange's equation of L for the line's kinetic energy above,
// its strain energy U(y; L), its weight, the drum's inertia J(L) / r^2 (the rope on it included)
// and the torque, positive reeling in.
#pragma once

#include <vector>

#include "bodies/model.hpp"
#include "linalg/band.hpp"

namespace rancf {

struct System;

struct Winch {
  int body = 0;             ///< flexible body
  int length = 0;           ///< time function of L(t)
  double length_set = 1.0;  ///< the unstretched length the body's arrays hold
  int n = 0, ku = 0;        ///< the body's coordinates and half bandwidth
  std::vector<double> c1;   ///< (2 ku + 1, n) band storage
  std::vector<double> c2;   ///< (2 ku + 1, n)
  std::vector<double> d2;   ///< (2 ku + 1, n)
  // a driven drum: L = y[drum]
  int drum = -1;          ///< the drum's coordinate in the system's y, or -1 (L(t) given)
  int torque = -1;        ///< time function of the torque on the drum [N m], reeling in
  double mass = 0.0;      ///< J / r^2 at the start (the rope then on the drum included) [kg]
  double radius = 1.0;    ///< the drum's radius [m]
  double rho_a = 0.0;     ///< the line's mass per unstretched length [kg/m]
  double weight[3] = {};  ///< rho_a g [N/m]
  int exit = 0;           ///< the body's coordinate of the exit node's position (x)
  /// a drum's convective weights gw d L_ref / L_s per Gauss point of its line's fluid terms
  /// (DrumFluid; n_el * n_qp, empty: no fluid)
  std::vector<double> convective;
};

struct WinchSet {
  std::vector<Winch> winches;
  std::vector<int> of_body;  ///< the winch of each flexible body, or -1
  int drums = 0;             ///< driven drums: coordinates after the rigid bodies
};

/// L, L', L'' at time t, and ratio = L / length_set.
struct WinchState {
  double ratio = 1.0, length = 1.0, rate = 0.0, acc = 0.0;
};

/// The winch of flexible body b, or null.
const Winch* winch_of(const System& s, std::size_t b);

/// A drum's state from the system's y, v, a (v, a may be null: at rest; y null: its start).
WinchState winch_state(const System& s, const Winch& w, double t, const double* y = nullptr,
                       const double* v = nullptr, const double* a = nullptr);

/// A model whose arrays are those of m stretched by ratio (kept in the work vectors).
struct ScaledBody {
  Model model;
  std::vector<double> s0, j0, k0, qr, mass, gravity;
};
const Model& scaled_model(const Model& m, double ratio, ScaledBody& out);

/// r += the convective inertia at (y, v); jac += ck d/dy + cv d/dv of it (jac may be null).
void winch_inertia(const Winch& w, const WinchState& st, const double* y, const double* v,
                   double ck, double cv, double* r, const BandView* jac);

/// The kinetic energy of the material outside the winch; m is the scaled model.
double winch_kinetic_energy(const Model& m, const Winch& w, const WinchState& st, const double* y,
                            const double* v);

/// The gravity energy -Q_g(t)^T y + Q_g(0)^T y_ref (the reference's weight at t = 0 is its zero;
/// the weight of the material outside the winch changes with L); m is the unscaled model.
double winch_gravity_energy(const Model& m, const WinchState& st0, const WinchState& st,
                            const double* y);

/// A driven drum's balance and its coupling to the line (docs/derivations/variable-length.md
/// §3): the residual R_d, and with the Jacobian coefficients ck, cv, ca: col (n) the line's rows
/// by the drum's coordinate, row (n) R_d by the line's coordinates, diag R_d by its own.
struct DrumTerms {
  double residual = 0.0;
  std::vector<double> col, row;
  double diag = 0.0;
};

/// base: the body's model (arrays at length_set), scaled: stretched to st.length; y, v, a the
/// body's (v, a null: statics); torque the torque's value; lf the load factor; c the mass-
/// proportional damping.
void drum_terms(const Model& base, const Model& scaled, const Winch& w, const WinchState& st,
                const double* y, const double* v, const double* a, double torque, double lf,
                double c, double ck, double cv, double ca, bool jacobian, DrumTerms& out);

/// The drum's kinetic energy 1/2 J(L) L'^2 / r^2 and the weight of the rope wound off it, whose
/// potential is taken at the exit: (L - L0) rho_a g . x_exit (y, v the system's).
double drum_kinetic_energy(const Winch& w, const double* y, const double* v);
double drum_gravity_energy(const Winch& w, const System& s, const double* y);

}  // namespace rancf
