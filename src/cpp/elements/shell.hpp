// RANCF Kirchhoff-Love shell elements on exact surfaces (docs/derivations/shell.md sec. 3-6).
//
// An element is the tensor product of two cable elements (eq. 3.2): four corner nodes of twelve
// coordinates [r, r_x, r_y, r_xy] (eq. 3.1), 48 an element.  Element coordinates run corner by
// corner (corner c = i + 2 j, i along u, j along v), then nodal vector k = g + 2 h (g, h = 1 for
// a gradient along u, v), then x, y, z: index 12 c + 3 k + d, the model's 12 node + 3 k + d.
// Nodal vector (c, k) has the shape function S = N_{2i+g}(xi) M_{2j+h}(eta), N and M the cable's
// (bodies/cable_shape.hpp) with each direction's weights and gradient scale.
//
// Strain energy (eqs. 4.5-4.7): Green-Lagrange membrane strains and curvature changes, a St.
// Venant-Kirchhoff plane-stress law in the reference metric, an n x n Gauss rule on the element;
// forces and tangent are the exact first and second variations (eqs. 4.8, 4.9).  Membrane
// strains are used as they are ("full"), as their element-local L2(dA) projections (eq. 5.1,
// "projected": eps_11 on degree (2, 3) in (xi, eta), eps_22 on (3, 2), eps_12 on (2, 2)), or as
// they are on a 3 x 3 rule ("reduced", the fallback of sec. 5); bending always on the full rule.
// The mass and the loads per reference area are consistent (sec. 6).
//
// In the element registry (elements/registry.hpp) the family "shell" is a Model holding these
// elements (ShellData) and gathering an element's 48 coordinates through their connectivity
// (bodies/model.hpp: Connectivity); its kernel calls element_forces and element_energy.
#pragma once

#include <cstdint>
#include <vector>

namespace rancf {

inline constexpr int kShellShapes = 16;  ///< nodal vectors of an element
inline constexpr int kShellDofs = 48;    ///< coordinates of an element

/// Membrane strains: as they are, projected (docs/derivations/shell.md eq. 5.1), or as they are
/// on a reduced kReducedGauss x kReducedGauss rule (sec. 5, the fallback).
enum class MembraneStrains : int { full = 0, projected = 1, reduced = 2 };

/// Gauss points per direction of the reduced membrane rule (one less than a cubic's full 4).
inline constexpr int kReducedGauss = 3;

/// Material and section of a shell body.
struct ShellMaterial {
  double thickness = 0.0;
  double youngs_modulus = 0.0;
  double poisson_ratio = 0.0;
  double density = 0.0;
};

/// A mesh of shell elements and its material (filled from a ShellRecord).
struct ShellInput {
  int n_nodes = 0;
  int gauss = 5;                           ///< Gauss points per direction
  std::vector<std::int64_t> connectivity;  ///< (n_el, 4): node of corner i + 2 j
  std::vector<double> weights_u;           ///< (n_el, 4) cubic weights along u
  std::vector<double> weights_v;           ///< (n_el, 4) cubic weights along v
  std::vector<double> scales;              ///< (n_el, 2) gradient scales l_u, l_v (eq. 3.4)
  std::vector<double> q0;                  ///< (12 n_nodes) reference coordinates
  ShellMaterial material;
  MembraneStrains membrane = MembraneStrains::projected;
  [[nodiscard]] int n_el() const { return static_cast<int>(connectivity.size() / 4); }
};

/// Shape functions and reference data at one Gauss point of one element.
struct ShellPoint {
  double s[6][kShellShapes];  ///< S, S_1, S_2, S_11, S_22, S_12 (1 = xi, 2 = eta)
  double w;                   ///< Gauss weight
  double wda;                 ///< Gauss weight times the reference |A1 x A2| (eq. 4.3)
  double a_ref[3];            ///< A_11, A_22, A_12
  double b_ref[3];            ///< B_11, B_22, B_12
  double d[6];                ///< plane-stress law per unit thickness (eq. 4.6), Voigt [11, 22,
                              ///< 2 12], upper triangle D11 D12 D13 D22 D23 D33
};

/// A sparse matrix as triplets in the model's numbering.
struct Triplets {
  std::vector<std::int64_t> rows, cols;
  std::vector<double> values;
};

/// The elements of one shell body.
class ShellElements {
 public:
  /// Checks the input (one line naming the field) and sets up the reference data.
  explicit ShellElements(ShellInput in);

  [[nodiscard]] int n() const { return 12 * in_.n_nodes; }
  [[nodiscard]] int n_el() const { return in_.n_el(); }
  [[nodiscard]] const ShellInput& input() const { return in_; }

  /// Strain energy W(q) (eq. 4.7).
  [[nodiscard]] double energy(const double* q) const;
  /// Internal forces dW/dq into f (n values, overwritten).
  void forces(const double* q, double* f) const;
  /// Tangent d2W/dq2 as triplets (2304 an element in element order, duplicates summed by the
  /// caller); the elements shared among the assembly threads (bodies/threads.hpp).
  [[nodiscard]] Triplets tangent(const double* q) const;
  /// Consistent mass matrix (sec. 6) as triplets.
  [[nodiscard]] Triplets mass() const;
  /// Consistent nodal forces of a constant force p (3) per reference area into f (n values).
  void area_load(const double* p, double* f) const;

  /// Follower pressure p along the current normal a3 (per current area, sec. 6): the forces
  /// Q = int p S^T a3t dxi deta into f (n values) and, if t is not null, dQ/dq (not symmetric)
  /// as triplets into t.
  void pressure(const double* q, double p, double* f, Triplets* t) const;

  /// One element: its 48 coordinates from q.
  void gather(int el, const double* q, double* e) const;
  [[nodiscard]] double element_energy(int el, const double* e) const;
  /// One element's forces fe (48) and, if ke is not null, tangent ke (48 x 48 row-major).
  void element_forces(int el, const double* e, double* fe, double* ke) const;

 private:
  ShellInput in_;
  int n_qp_ = 0;                  ///< Gauss points of an element (bending, mass, loads)
  int n_mp_ = 0;                  ///< Gauss points of an element's membrane energy
  std::vector<ShellPoint> pts_;   ///< (n_el, n_qp)
  std::vector<ShellPoint> mpts_;  ///< (n_el, n_mp): the membrane's (the same rule unless reduced)
  std::vector<double> proj_;      ///< (n_el, 3, n_mp, n_mp) membrane projections (eq. 5.1; I)

  [[nodiscard]] const ShellPoint* points(int el) const {
    return pts_.data() + static_cast<std::size_t>(el) * static_cast<std::size_t>(n_qp_);
  }
  [[nodiscard]] const ShellPoint* membrane_points(int el) const {
    return mpts_.data() + static_cast<std::size_t>(el) * static_cast<std::size_t>(n_mp_);
  }
  [[nodiscard]] const double* projection(int el) const {
    return proj_.data() + static_cast<std::size_t>(el) * 3 * static_cast<std::size_t>(n_mp_) *
                              static_cast<std::size_t>(n_mp_);
  }
  /// Shape functions and reference data of element el on the rule (x, w) x (x, w) into out.
  void set_up_points(int el, const std::vector<double>& x, const std::vector<double>& w,
                     ShellPoint* out) const;
  void set_up_projection(int el, const std::vector<double>& x);
  /// The membrane strains (projected if so chosen) at the membrane points, (n_mp, 3).
  [[nodiscard]] std::vector<double> membrane_strains(int el, const double* e) const;
  /// The membrane's forces and (if ke is not null) tangent added to fe, ke.
  void add_membrane(int el, const double* e, double* fe, double* ke) const;
};

/// Gauss-Legendre points x and weights w on [0, 1] (n points, exact to degree 2 n - 1).
void gauss_legendre01(int n, std::vector<double>& x, std::vector<double>& w);

}  // namespace rancf
