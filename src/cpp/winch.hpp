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
#pragma once

#include <vector>

#include "band.hpp"
#include "model.hpp"

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
};

struct WinchSet {
  std::vector<Winch> winches;
  std::vector<int> of_body;  ///< the winch of each flexible body, or -1
};

/// L, L', L'' at time t, and ratio = L / length_set.
struct WinchState {
  double ratio = 1.0, length = 1.0, rate = 0.0, acc = 0.0;
};

/// The winch of flexible body b, or null.
const Winch* winch_of(const System& s, std::size_t b);

WinchState winch_state(const System& s, const Winch& w, double t);

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

}  // namespace rancf
