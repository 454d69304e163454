// Places of a system: where joints, springs and loads attach, as functions of the coordinates of
// the body that carries them (docs/derivations/systems.md section 3).
//
// A place has a position x (world, 3 components; z = 0 in 2D) and up to three frame vectors f_k
// (unit, world), each with its derivatives with respect to the place's local coordinates:
//   ground     none; x = the ground point, f = (e_x, e_y, e_z), or the columns of R(t) for a
//              turning frame (a rotating clamp: docs/derivations/clamp-paths.md sec. 2)
//   cable      a cable node (r, r_x): x = r; f_0 = t = r_x / |r_x|; in 2D also f_1 = e_z x t, f_2 =
//   e_z rod        a rod node (r, r_x, phi): x = r; (t, m1, m2), the nodal triad by smallest
//   rotation
//              from the node's reference triad (docs/derivations/rod.md section 2)
//   beam       a beam node (x, y, theta): psi = theta + psi_0; f_0 = (cos psi, sin psi), f_1, e_z
//   rigid2d    (x_c, y_c, theta): x = x_c + R(theta) s, f = columns of R(theta) and e_z
//   rigid3d    (x_c, p) with a unit quaternion p = (p0, p1, p2, p3): x = x_c + R(p) s, f = R(p) e_k
//   mass       a point mass x: no frame
#pragma once

namespace rancf {

enum class PlaceKind : int {
  ground = 0,
  cable = 1,
  rod = 2,
  beam = 3,
  rigid2d = 4,
  rigid3d = 5,
  mass = 6
};

/// Largest number of local coordinates of a place: 7 for a rod node; a node of a reduced model
/// (model.hpp: Reduction) depends on a window of up to 24 model coordinates
/// (rancf.mesh.continuity).
inline constexpr int kMaxLocal = 24;

/// What a place needs besides the local coordinates.
struct PlaceInfo {
  PlaceKind kind = PlaceKind::ground;
  int dim = 2;
  double point[3] = {0.0, 0.0, 0.0};  ///< ground: the point; rigid: the point in the body frame
  const double* tref = nullptr;       ///< rod: the node's reference tangent
  const double* m1ref = nullptr;      ///< rod: the node's reference director
  double angle0 = 0.0;                ///< beam: the node's reference tangent angle
  /// ground: its frame's rotation from the world axes (row-major; the identity unless turned)
  double frame[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  /// false: the position and its derivatives alone (nf = 0; rigid bodies still get frames),
  /// for joints that use no frame (a pin)
  bool frames = true;
};

/// The derivatives are set (eval_place, place_local) for the first n local coordinates only:
/// a joint's place has a handful of the kMaxLocal, and clearing all of them at every
/// evaluation cost more than the joint equations themselves.
struct PlaceEval {
  int n = 0;                      ///< local coordinates
  double x[3] = {0.0, 0.0, 0.0};  ///< position
  double dx[3][kMaxLocal];        ///< d x_i / d local_j (j < n)
  int nf = 0;                     ///< frame vectors (0, 1 or 3)
  double f[3][3] = {};            ///< f[k][i]: component i of frame vector k
  double df[3][3][kMaxLocal];     ///< d f[k][i] / d local_j (j < n)
};

/// Number of local coordinates of a place kind.
int place_size(PlaceKind kind, int dim);

/// Position, frame vectors and their first derivatives at local coordinates `local`.
void eval_place(const PlaceInfo& info, const double* local, PlaceEval& out);

/// Rotation matrix R (row-major) of a turning ground frame: 2D rot[0] the angle about z; 3D
/// rot[0..2] the rotation vector (Rodrigues: R = I + sin|r| K + (1 - cos|r|) K^2, K = [r/|r|]x).
void rotation_matrix(int dim, const double* rot, double* R);

/// Rotation matrix R(p) (row-major) of a quaternion p (scalar first; exact for |p| = 1) and, if
/// dR is not null, dR[j] = dR/dp_j (4 matrices, row-major).
void quaternion_rotation(const double* p, double* R, double (*dR)[9]);

}  // namespace rancf
