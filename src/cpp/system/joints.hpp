// Joint equations g(q_A, q_B, t) = 0 between two places and their Jacobians
// (docs/derivations/systems.md section 3).  Every row is a dot product of positions and frame
// vectors of the two places (places.hpp), so its Jacobian follows by the product rule from the
// places' derivatives:
//
//   pin        x_A - x_B                                        (dim rows)
//   fixed      pin, and 2D: sin(psi_A - psi_B - beta_0)          (+1: 3 rows)
//                        3D: a_0 . c_1, a_1 . c_2, a_2 . c_0      (+3: 6 rows)
//              a_k = f_k(A), c_k = sum_j rel[k][j] f_j(B): A's reference axes carried by B
//   tangent    pin, and t_A . n_1, t_A . n_2 (3D: a cable end's tangent held by a frame; 5 rows)
//   revolute   pin, and e_A . n_1, e_A . n_2 (3D: the axis e_A of A normal to B's n_1, n_2)
//   slider     (x_A - x_B) . n_i for B's normals n_i of the line (2D: 1 row, 3D: 2 rows)
//   sliding    a flexible body through B (sliding.hpp: dim rows and its material coordinate)
//   driven     an extra row: sin(angle - beta_0 - theta(t)); 2D the angle psi_A - psi_B, 3D the
//              angle about e_A from w_B to w_A (w normal to the axis, equal in the reference)
// Coefficient vectors (e_A, n_i, w) are given in the frames of their places, fixed at assembly.
#pragma once

#include "system/places.hpp"

namespace rancf {

enum class JointKind : int {
  pin = 0,
  fixed = 1,
  tangent = 2,
  revolute = 3,
  slider = 4,
  sliding = 5
};

struct JointInfo {
  JointKind kind = JointKind::pin;
  int dim = 2;
  bool driven = false;          ///< an angle row driven by theta(t)
  double beta0 = 0.0;           ///< reference angle (2D rows; 3D driven row)
  double rel[3][3] = {};        ///< fixed 3D: rel[k][j] = a_k^0 . b_j^0
  double axis_a[3] = {};        ///< revolute: e_A in A's frame; tangent: unused
  double normals_b[2][3] = {};  ///< revolute, tangent, slider: n_i in B's frame
  double w_a[3] = {};           ///< driven 3D: w_A in A's frame
  double w_b[3] = {};           ///< driven 3D: w_B in B's frame
};

inline constexpr int kMaxJointRows = 7;

/// Rows of a joint.
int joint_rows(const JointInfo& j);

/// g (rows) and its Jacobian jac (rows x (n_A + n_B), row-major) at the places' values;
/// theta: the driven angle at this time (ignored if not driven).  jac null: g alone.
void eval_joint(const JointInfo& j, const PlaceEval& a, const PlaceEval& b, double theta, double* g,
                double* jac);

}  // namespace rancf
