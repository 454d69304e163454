// Rigid bodies and point masses: inertial forces and their derivatives.
//
// 2D rigid body (x, y, theta): M = diag(m, m, J), constant.
// 3D rigid body (x_c, p) with a unit quaternion p (normalized by a constraint row of the system):
// with the body angular velocity w = 2 G(p) p' (Nikravesh's L matrix, linear in p, G(a) b =
// -G(b) a) the kinetic energy is 1/2 m |x_c'|^2 + 1/2 w^T J w = 1/2 m |x_c'|^2 + 2 p'^T G^T J G p',
// and Lagrange's equations give the generalized inertial force
//   F_p = 4 G(p)^T J G(p) p'' + 8 G(p')^T J G(p) p'  (+ kappa p (p . p''))
// The last term regularizes the block (4 G^T J G has rank 3): it acts along p, which the
// normalization constraint's multiplier absorbs exactly, so the motion is unchanged.
// A point mass: M = m I.
#pragma once

namespace rancf {

/// Inertia of one rigid body or point mass.
struct RigidInertia {
  int dim = 2;
  bool point_mass = false;
  double mass = 0.0;
  double inertia[3] = {0.0, 0.0, 0.0};  ///< 2D: inertia[0] = J about the centre of mass
};

/// Coordinates of the body (2D rigid 3, 3D rigid 7, point mass dim).
int rigid_size(const RigidInertia& b);

/// f = F(q, v, a) (size n) and, if k is not null, k = ck dF/dq + cv dF/dv + ca dF/da (n x n,
/// row-major).
void rigid_inertial_force(const RigidInertia& b, const double* q, const double* v, const double* a,
                          double ck, double cv, double ca, double* f, double* k);

/// Kinetic energy.
double rigid_kinetic_energy(const RigidInertia& b, const double* q, const double* v);

/// Angular momentum about the origin (3 components; 2D: only z).
void rigid_angular_momentum(const RigidInertia& b, const double* q, const double* v, double* out);

}  // namespace rancf
