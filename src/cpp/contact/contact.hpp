// Contact of flexible bodies with obstacles: penalty line contact along the curve with regularized
// Coulomb friction (the method: docs/guide/contact.md).
//
// A flexible body is a tube of radius rt about its centre line r(xi) = sum_k N_k(xi) e_k.  At
// n_c Gauss points per element (weights w = gauss weight x reference |r0'|: the integral over the
// reference arc length) the gap g to an obstacle is
//   plane     g = a . (r - c) - rt                          (a: unit normal, c: a point)
//   cylinder  g = |P (r - c)| - R - rt, P = I - a a^T         (a: unit axis; 2D: a circle, a = e_z)
//   sphere    g = |r - c| - R - rt
// with the unit normal n = dg/dr and H = d2g/dr2 = (P - n n^T) / |P (r - c)| (plane: 0).  The
// force per reference length on the body at a point is F = p n + f_t with the pressure
//   p = <p_k(g) <1 - chi g'> - s c_n g'>   (g' = n . u; Hunt & Crossley 1975 damping and a
//                                            linear normal damping c_n while in contact, as
//                                            MoorDyn's seabed cBot, ramped in over the
//                                            onset, s = min(p_k / (k d / 2), 1): no jump
//                                            where a point comes into contact; never pulling)
// of a penalty of stiffness k with a smooth onset over a depth d (C1, convex potential Phi):
//   p_k = 0 for g >= 0,  k g^2 / (2 d) for -d <= g < 0,  k (-g - d/2) below,
// so that a point resting under a light load q sinks to sqrt(2 d q / k) with the stiffness
// sqrt(2 k q / d), growing with the load (as Hertz's contact does), not to q / k with k: its
// stiffness does not switch on and off under the Newton iterations' round-off; and the
// Coulomb friction regularized by the slip velocity eps,
//   f_t = -mu p v_t / sqrt(|v_t|^2 + eps^2),  v_t = (I - n n^T) u,
// u the velocity of the point relative to the obstacle's material point there.
//
// In a time step (velocities given and y1 apart from yf) the elastic pressure is the mean of p_k
// over [ga, g1], g1 = g(y1), ga = 2 gf - g1, an interval centred on the alpha point's gap gf
// (with ContactSet::step_alpha_f the step's gap: the blend of the gaps at the step's ends)
// (the damping factor multiplies it): on the linear piece exactly p_k(gf), the generalized-
// alpha force; with rho_inf = 1 (the midpoint rule, ga = g(y0) for blended gaps) the discrete
// gradient (Phi(g0) - Phi(g1)) / (g1 - g0), so that the penalty's energy balance is exact for a
// plane and to O(dy^3) for curved obstacles (Laursen & Chawla 1997); and a point that comes into
// contact within a step meets a pressure that grows smoothly with g1.  Statics (no velocities):
// p_k(g), no friction, no damping.
//
// Tangents: exact for fixed obstacles (2x2 / 3x3 point matrices mapped by N) and for obstacles
// carried by planar rigid bodies (the law's objectivity, contact.cpp carried_tangent; the body's
// velocity field differentiated over its coordinates by central differences once per pair);
// for an obstacle carried by a 3D rigid body by central differences (steps min(1e-6, 1e-4 d)
// (1 + |z|), velocities 1e-4 eps (1 + |z|)) of the exact point forces over the point's
// position and the body's coordinates, as system_assembly.cpp does for rigid points.
// Couplings between an element and a body go through the sink (add_matrix: the border).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "linalg/bordered.hpp"
#include "system/system.hpp"

namespace rancf {

enum class ObstacleKind : int { plane = 0, cylinder = 1, sphere = 2 };

struct Obstacle {
  ObstacleKind kind = ObstacleKind::plane;
  int body = -1;                      ///< rigid body carrying it (index), or -1: fixed
  double point[3] = {0.0, 0.0, 0.0};  ///< plane point / centre (world; body frame if carried)
  double dir[3] = {0.0, 0.0, 1.0};    ///< plane normal / cylinder axis, unit (same frame)
  double radius = 0.0;                ///< cylinder, sphere
};

/// Contact points of one flexible body (n_c == 0: the body has none).
struct ContactBody {
  int n_c = 0;
  std::vector<double> N;   ///< shape functions at the points, (n_el, n_c, 4)
  std::vector<double> N1;  ///< their xi-derivatives, (n_el, n_c, 4)
  std::vector<double> gw;  ///< Gauss weights on [0, 1], (n_c)
  std::vector<double> w;   ///< Gauss weight x reference |r0'|, (n_el, n_c)
  double radius = 0.0;     ///< tube radius
  // contact between flexible bodies (body_contact.hpp): the element curves anywhere
  std::vector<double> weights;  ///< rational weights of the elements, (n_el, 4)
  std::vector<double> scales;   ///< gradient scales of the elements, (n_el)
  std::vector<double> arc0;     ///< reference arc length at each element's start, (n_el + 1)
};

/// A flexible body against an obstacle.
struct ContactPair {
  int flex = 0, obstacle = 0;
  double stiffness = 0.0;       ///< k: force per reference length per penetration [N/m^2]
  double onset = 0.0;           ///< d: depth of the smooth onset of the pressure [m]
  double damping = 0.0;         ///< chi, Hunt-Crossley [s/m]
  double damping_normal = 0.0;  ///< c_n = c D, linear normal damping per length [N s/m^2]
  double friction = 0.0;        ///< Coulomb coefficient mu
  double slip_velocity = 1.0;   ///< eps of the friction's regularization [m/s]
};

/// Two flexible bodies in contact (a == b: self-contact; body_contact.hpp).
struct BodyPair {
  int a = 0, b = 0;
  double stiffness = 0.0;      ///< k [N/m^2]
  double onset = 0.0;          ///< d [m]
  double friction = 0.0;       ///< Coulomb coefficient mu
  double slip_velocity = 1.0;  ///< eps of the friction's regularization [m/s]
};

/// A contact point of a body pair's side A near an element of side B (body_broad.hpp).
struct NearPoint {
  int pair = 0, dir = 0;  ///< the body pair and its order (0: a against b, 1: b against a)
  int e = 0, q = 0, f = 0;
  double xi = -1.0;                           ///< its last closest point on f (-1: none yet)
  std::array<double, 2> xi_ends{-1.0, -1.0};  ///< the same at the step's end and start
  /// a lower bound of its gap to f when the drift_el of e and f (NearList) summed to `drift`
  double gap = -1e300, drift = 0.0;
};

/// The points of the body pairs that can touch an element while no element has moved by
/// more than a margin (body_broad.hpp update_near), and their last closest points.
struct NearList {
  std::mutex mu;
  bool valid = false;
  double margin = 0.0;
  double moved = 0.0;       ///< the largest motion of a control point in the step (y to y1, y0)
  std::vector<double> ref;  ///< the elements' Bezier control points where it was made
  std::vector<int> start;   ///< the first element of each body in the arrays below
  std::vector<double> moved_el;  ///< per element: the largest motion of its control points in
                                 ///< the step (as `moved`)
  /// per element: the sum over the assemblies so far of the largest motion of its control
  /// points since the assembly before (at the control points `last`), a bound of its motion
  /// between any two assemblies
  std::vector<double> drift_el, last;
  std::vector<NearPoint> points;
};

struct ContactSet {
  std::vector<ContactBody> bodies;  ///< one per flexible body of the system
  std::vector<Obstacle> obstacles;
  std::vector<ContactPair> pairs;
  std::vector<BodyPair> body_pairs;
  /// alpha_f of the time steps whose alpha points (yf, with y1 their end) the contact forces
  /// are given at: a point's gap of a step (obstacles fixed or carried, body pairs) is then
  /// the blend of the gaps at the step's start and end, (1 - af) g(y1) + af g(y0),
  /// y0 = (yf - (1 - af) y1) / af, never the gap of a blend of positions (time-integration.md
  /// sec. 4, TI.16); 0: the gap at yf.
  double step_alpha_f = 0.0;
  /// the body pairs' near points, kept between assemblies (shared by copies)
  std::shared_ptr<NearList> near = std::make_shared<NearList>();
};

/// Receives a small dense matrix K (k x k, row-major) over global indices idx (add_matrix).
using MatrixSink = std::function<void(const int* idx, int k, const double* K)>;

/// Contact forces into the balance r (r -= generalized contact forces) at (yf, vf) (vf null:
/// statics) with the step's mean pressure between yf and y1 (y1 == yf: the pressure at yf), and
/// their Jacobian with respect to y1 (ck d/dyf + cv d/dvf + c1 d/dy1, AssemblyTerms): fixed
/// obstacles' straight into the flexible bodies' band blocks of lu (if not null; else into add),
/// carried obstacles' (couplings with the body) into add.  No Jacobian if both are null.
void assemble_contact(const System& s, const ContactSet& c, const double* yf, const double* vf,
                      const double* y1, const AssemblyTerms& tm, double* r, BorderedLU* lu,
                      const MatrixSink* add);

/// The penalty's potential energy sum Phi(g) w at y.
double contact_energy(const System& s, const ContactSet& c, const double* y);

/// Values per obstacle of contact_outputs.
inline constexpr int kContactOutputs = 11;

/// Per obstacle (kContactOutputs values each): the force of the obstacle on the bodies, normal
/// (3) and friction (3) parts, its moment about the obstacle's point (3), the contact length
/// (current arc length of the points in contact, by the points' quadrature) and the largest
/// penetration, at (y, v) (v null: no friction).  With y1 not null, (y, v) are a time step's
/// alpha point and y1 its end: the forces are those the step applies (the step's mean
/// pressure, assemble_contact).
void contact_outputs(const System& s, const ContactSet& c, const double* y, const double* v,
                     const double* y1, double* out);

/// The points of pair k at (y, v): position (3), gap, pressure, friction force (3) per point,
/// 8 values each (n_el n_c points).
void contact_points(const System& s, const ContactSet& c, int k, const double* y, const double* v,
                    double* out);

}  // namespace rancf
