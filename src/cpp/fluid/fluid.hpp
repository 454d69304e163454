// Lines in a fluid: buoyancy, Morison drag, Froude-Krylov and added mass, and distributed loads
// on flexible bodies, integrated over each element (docs/derivations/fluid.md).
//
// At a Gauss point of an element with position r, r' = a (tangent t = a / |a|), velocity v and
// acceleration acc, all per reference length (weight w = gw J0):
//   drag      f_D = 1/2 rho d Cdn |w_n| w_n + 1/2 rho pi d Cdt |w_t| w_t,  w = u(r, t) - v
//   inertia   f_I = rho A [(I - t t^T)((1 + Can) du - Can acc) + t t^T ((1 + Cat) du - Cat acc)]
//   buoyancy  f_B = -rho A g where the point is below the free surface
//   loads     f_L = F factor(t)
// with A = pi d^2 / 4; the generalized force Q = sum w S^T f.  The Jacobian of -Q with respect
// to the element coordinates (through r, t and the fluid's kinematics), velocities and
// accelerations is exact (fluid.md section 4).
#pragma once

#include <vector>

#include "bodies/model.hpp"
#include "linalg/band.hpp"
#include "system/time_function.hpp"

namespace rancf {

/// Linear (Airy) waves, a sum of components i: elevation a_i cos(k_i x.e - omega_i t - phi_i)
/// about the still surface (one regular wave: one component of amplitude H/2 and phase 0).
struct Waves {
  bool on = false;
  std::vector<double> amplitude;    ///< a_i
  std::vector<double> omega;        ///< omega_i = 2 pi / T_i
  std::vector<double> k;            ///< wave numbers (k tanh(k h) = omega^2 / g; 0: a mean level)
  std::vector<double> phase;        ///< phi_i
  double depth = 0.0;               ///< h, still surface to the bottom
  double dir[3] = {1.0, 0.0, 0.0};  ///< unit horizontal direction of travel
};

/// The fluid the bodies are in.
struct FluidField {
  double density = 0.0;
  bool has_surface = false;  ///< false: every point is submerged
  double surface = 0.0;      ///< still surface height (the last coordinate)
  double current[3] = {0.0, 0.0, 0.0};
  std::vector<double> profile_z;  ///< current profile: heights (increasing), or empty
  std::vector<double> profile_u;  ///< (n, 3) velocities at those heights
  Waves waves;
};

/// A force per reference length times a time function (-1: constant).
struct DistributedLoad {
  double force[3] = {0.0, 0.0, 0.0};
  int factor = -1;
};

/// One flexible body in the fluid: its hydrodynamic coefficients and the quadrature of its
/// elements (shape functions S and S' at the points, weights, reference |r0'|).
struct LineFluid {
  int body = 0;
  bool hydro = false;  ///< the fluid acts (false: only distributed loads)
  double diameter = 0.0, cdn = 0.0, cdt = 0.0, can = 0.0, cat = 0.0;
  int n_qp = 0;
  std::vector<double> n0, n1;  ///< (n_el, n_qp, 4)
  std::vector<double> gw;      ///< (n_qp)
  std::vector<double> j0;      ///< (n_el, n_qp)
  std::vector<DistributedLoad> loads;
};

struct FluidSet {
  FluidField field;
  double gravity[3] = {0.0, 0.0, 0.0};
  std::vector<LineFluid> lines;
};

/// The fluid's velocity u and acceleration du at r, time t, with their derivatives with respect
/// to r (du_dr[i][j] = d u_i / d r_j); wet: the point is below the free surface.
struct FluidPoint {
  double u[3] = {0.0, 0.0, 0.0}, du[3] = {0.0, 0.0, 0.0};
  double u_r[3][3] = {}, du_r[3][3] = {};
  bool wet = true;
};
void fluid_point(const FluidField& f, int dim, const double* r, double t, bool waves,
                 FluidPoint& out);

/// The free surface's height at the horizontal position of r (its last coordinate ignored) at
/// time t: the still surface plus the waves' elevation.
double surface_elevation(const FluidField& f, int dim, const double* r, double t);

/// A driven drum's share of its line's fluid loads (docs/derivations/variable-length.md §3.5):
/// the generalized force of the loads f (per unstretched length) on the line's length L is
/// sum_q c_q f.r' with c_q = gw_q d_q L_ref / L_s (the material's convective move per L at the
/// Gauss point), so the drum's balance R_L gains -sum_q c_q f.r'.
struct DrumFluid {
  const double* c = nullptr;  ///< c_q per Gauss point (n_el * n_qp)
  double residual = 0.0;      ///< += -sum_q c_q f.r'
  double* row = nullptr;      ///< (the model's n) += ck d/dy + cv d/dv + ca d/dacc of it, or null
};

/// What assemble_line needs of the time step.
struct LineTerms {
  double t = 0.0;
  double ck = 1.0, cv = 0.0, ca = 0.0;
  double load_factor = 1.0;  ///< on drag, buoyancy and loads (statics' load stepping)
  const std::vector<TimeFunction>* tfs = nullptr;
  /// the unstretched length over the one the line's arrays hold (a winch's L(t) / length_set):
  /// every term is per unstretched length, so its measure j0 dxi scales with it
  double length_ratio = 1.0;
  DrumFluid* drum = nullptr;  ///< a driven drum's share of the loads (its line), or null
};

/// Add -Q of line `line` of model m at (y, v, acc) (v, acc null: statics, no inertia, no waves)
/// into r (the model's n rows), its Jacobian ck d/dy + cv d/dv + ca d/dacc into jac (if not
/// null), and the total fluid force (drag, inertia, buoyancy; not the loads) into force (3, if
/// not null).
void assemble_line(const Model& m, const FluidSet& fs, const LineFluid& line, const double* y,
                   const double* v, const double* acc, const LineTerms& terms, double* r,
                   const BandView* jac, double* force);

}  // namespace rancf
