// A multibody system as the compiled core sees it (docs/derivations/systems.md sections 1, 3, 4).
//
// Coordinates y of all bodies stacked body by body: each flexible body's model coordinates (a
// Model: its chain, supports held by elimination), then every rigid body (2D: x, y, theta; 3D:
// x_c, a unit quaternion p) and point mass (x), then the length of each driven drum (winch.hpp).
// Joints are constraint rows g(y, t) = 0 with
// Lagrange multipliers; a 3D rigid body adds the row (p . p - 1) / 2.  The equations of motion
//   M a + c M v + F_in + f_int(y) - f_ext(t, y) + f_springs(y, v) + G(y)^T lambda = 0,
//   g(y, t) = 0
// are assembled into the blocks of a bordered band matrix (bordered.hpp): a band block per
// flexible body, a dense (full band) block per rigid body or point mass; joint Jacobians and
// couplings between bodies (springs, the second derivatives of joints) border it.
//
// The parts' structs (RigidInertia, PlaceRef, JointData, SpringData, PlaceLoad, TimeFunction,
// Prescribed, LinearTerm) are filled field by field from the Python records of the same names in
// rancf.kernels.records (bindings_records.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "bodies/model.hpp"
#include "linalg/bordered.hpp"
#include "system/joints.hpp"
#include "system/places.hpp"
#include "system/rigid.hpp"
#include "system/time_function.hpp"

namespace rancf {

struct ContactSet;  // contact.hpp
struct FluidSet;    // fluid.hpp
struct WinchSet;    // winch.hpp
struct SlidingSet;  // sliding.hpp

/// A place: on a flexible body's node (kind cable/rod/beam), a rigid body or point mass, or the
/// ground (optionally moving: point + u(t), its frame turned by R(t)).
struct PlaceRef {
  PlaceKind kind = PlaceKind::ground;
  int body = -1;  ///< flexible body (node kinds) or rigid body/mass index
  int node = 0;   ///< node of a flexible body
  double point[3] = {0.0, 0.0, 0.0};
  int motion = -1;  ///< ground: time function of the displacement (dim components), or -1
  /// ground: time function of the frame's rotation from the world axes (2D: the angle about z;
  /// 3D: the rotation vector), or -1 (places.hpp: rotation_matrix)
  int rotation = -1;
  double angle0 = 0.0;  ///< beam node: its reference tangent angle
};

struct JointData {
  JointInfo info;
  int a = 0, b = 0;  ///< place indices
  int angle = -1;    ///< driven: the time function of the angle
  int body = -1;     ///< sliding: the flexible body through place b (place a: its node 0)
};

struct SpringData {
  int a = 0, b = 0;
  double stiffness = 0.0, damping = 0.0, length = 0.0;
  int law = -1;  ///< the time function of its tension law T(e) (spring_law.hpp), or -1: k e
};

/// A force (and, on rigid bodies, a torque) at a place, times a time function (-1: constant).
struct PlaceLoad {
  int place = 0;
  double force[3] = {0.0, 0.0, 0.0};
  double torque[3] = {0.0, 0.0, 0.0};
  int factor = -1;
};

/// A held coordinate that follows a time function: y[coord] = base + u_comp(t).
struct Prescribed {
  int coord = 0;
  int tf = 0;
  int comp = 0;
  double base = 0.0;
};

/// A place's local coordinates in y: their global indices (n of them) and the map
/// local(q) = T local(y) (nq x n) of a flexible node's rotated blocks, or of a reduced model's
/// node (model.hpp: Reduction); identity elsewhere.
struct PlaceMap {
  int n = 0;
  int nq = 0;            ///< the place's own coordinates (place_size)
  bool identity = true;  ///< T is the identity (no rotated block)
  bool reduced = false;  ///< a reduced model's node: every local may turn its frame
  int index[kMaxLocal] = {};
  double T[kMaxLocal][kMaxLocal] = {};
};

/// A term of a linear constraint row: row (0-based among the linear rows) gets coef * y[col].
/// Linear rows close a closed flexible body (its last stored node is its first: the seam's
/// coordinates are tied), with a constant Jacobian.
struct LinearTerm {
  int row = 0;
  int col = 0;
  double coef = 0.0;
};

struct System {
  int dim = 2;
  std::vector<const Model*> flex;
  std::vector<RigidInertia> rigid;
  std::vector<PlaceRef> places;
  std::vector<JointData> joints;
  std::vector<SpringData> springs;
  std::vector<PlaceLoad> loads;
  std::vector<TimeFunction> tfs;
  std::vector<Prescribed> prescribed;
  std::vector<LinearTerm> linear;  ///< linear constraint rows (after the joints and quaternions)
  int n_linear = 0;                ///< number of linear rows
  double gravity[3] = {0.0, 0.0, 0.0};  ///< on rigid bodies and point masses
  double damping = 0.0;                 ///< mass-proportional damping of every body
  /// Stiffness-proportional damping beta of the flexible bodies: the force beta K_T(y) v
  /// (system_assembly.cpp, stiffness_damping).
  double stiffness_damping = 0.0;
  const double* y_ref = nullptr;        ///< (n) reference coordinates (gravity potential zero)
  const ContactSet* contact = nullptr;  ///< obstacles and contact pairs (contact.hpp), or none
  const FluidSet* fluid = nullptr;      ///< fluid loads and distributed loads (fluid.hpp), or none
  const WinchSet* winches = nullptr;    ///< winches at ends of cable bodies (winch.hpp), or none
  const SlidingSet* sliding = nullptr;  ///< element geometry of bodies with sliding joints

  // derived by setup()
  int n = 0, m = 0;
  std::vector<int> offset;     ///< flexible bodies, rigid bodies, drums: first coordinate
  std::vector<int> joint_row;  ///< first constraint row of each joint
  /// The multiplier slots that hold sliding joints' material coordinates (sliding.hpp): not
  /// multipliers (kept by initial_acceleration), and their rows are not constraints.
  std::vector<int> slots;
  std::vector<int> norm_row;        ///< rigid bodies: the quaternion row, or -1
  int linear_row = 0;               ///< first linear row
  std::vector<std::uint8_t> fixed;  ///< (n) held coordinates
  std::vector<int> block_size, block_ku;
  std::vector<PlaceMap> maps;  ///< place_map of every place

  /// Offsets, sizes, rows, the held mask, the places' maps; call after filling the lists.
  void setup();
  [[nodiscard]] int rigid_offset(int r) const {
    return offset[flex.size() + static_cast<std::size_t>(r)];
  }
};

PlaceMap place_map(const System& s, const PlaceRef& p);
PlaceInfo place_info(const System& s, const PlaceRef& p, double t);
/// The place at time t with local coordinates u (y-space, map.n values); derivatives with
/// respect to them.
/// frames = false: the position and its derivatives alone where the place has them without a
/// frame (PlaceInfo::frames).
void place_local(const System& s, const PlaceRef& p, const PlaceMap& map, double t, const double* u,
                 PlaceEval& out, bool frames = true);
/// The same with the local coordinates gathered from the global y.
void place_at(const System& s, const PlaceRef& p, const PlaceMap& map, double t, const double* y,
              PlaceEval& out);

/// Constraint residual g (m) at (y, t); lam: the multipliers, whose slots hold the sliding
/// joints' material coordinates (null: no sliding joint); the slots' rows are zero.
void constraints(const System& s, const double* y, double t, double* g,
                 const double* lam = nullptr);

/// The balance at (yf, vf, am), time tf (vf, am null in statics):
///   r = M (am + c vf) + F_rot + F_rigid + f_int(yf) - f_ext(tf, yf) + f_springs + G(yf)^T lam
/// and the constraints g(y1, t1) into r[n .. n + m); if lu is not null, the Jacobian with respect
/// to (y1, lambda): ck d/dy + cv d/dv + ca d/da of the balance into the blocks and the border
/// (G(yf)^T as columns, G(y1) as rows, couplings between bodies as extra border unknowns).
/// Returns false if an evaluation is not finite.
struct AssemblyTerms {
  double ck = 1.0, cv = 0.0, ca = 0.0;  ///< coefficients of d/dy, d/dv, d/da
  double tf = 0.0;                      ///< time of the balance
  double t1 = 0.0;                      ///< time of the constraints
  double load_factor = 1.0;             ///< statics: the factor on the loads
  bool amplitude = false;               ///< statics: harmonic loads at their amplitude
  bool statics = false;  ///< statics (zero velocities even where am is given): winches at rest
  /// Outputs: the bodies' own terms only (elements, weight, inertia, fluid, contact), without
  /// the forces at places (point loads, loads at places, springs, joints)
  bool distributed_only = false;
  /// Outputs: contact forces taken at another state, a time step's alpha point (contact_yf,
  /// contact_vf) and end (contact_y1), instead of at (yf, vf, y1); no contact Jacobian then.
  const double* contact_yf = nullptr;
  const double* contact_vf = nullptr;
  const double* contact_y1 = nullptr;
  /// Outputs (may be null, n values each): the flexible bodies' element forces f_int alone
  /// (a winch's body at its length at tf; other rows untouched), and the bodies' own terms of
  /// r as distributed_only would give them without multipliers, taken from the same pass
  double* internal = nullptr;
  double* own = nullptr;
  /// Time steps of systems with contact (docs/derivations/time-integration.md sec. 4): the
  /// contact forces at the step's alpha point (contact_yf, contact_vf) and end (y1), with
  /// their Jacobian, times contact_scale (residual and Jacobian); c1 is the coefficient of
  /// the contact kernels' d/dy1 (ck and cv those of d/dyf and d/dvf).
  bool contact_step = false;
  double contact_scale = 1.0;
  double c1 = 1.0;
  /// The residual without the contact forces.
  bool skip_contact = false;
};

bool assemble_system(const System& s, const double* yf, const double* vf, const double* am,
                     const double* lambda, const double* y1, const AssemblyTerms& terms, double* r,
                     BorderedLU* lu);

/// The fluid's force (drag, inertia, buoyancy) on each flexible body at (y, v, a, t), world axes,
/// 3 values per body into out (v, a null: statics).
void fluid_forces(const System& s, const double* y, const double* v, const double* a, double t,
                  double* out);

}  // namespace rancf

namespace rancf {

/// The force and moment (about the place, world axes) that joint k exerts on its first place's
/// body at (y, t) with multipliers lam: the generalized forces Q = -G_A^T lambda on the place's
/// coordinates matched in the least-squares sense by Q_j = F . dx/du_j + M . w_j, w_j the
/// rotation rate of the place's frame per coordinate (exact for pins, fixed joints, revolutes
/// and sliders; the moment is zero at a place without a frame).
void joint_reaction(const System& s, int k, const double* y, double t, const double* lam,
                    double* force, double* moment);

}  // namespace rancf
