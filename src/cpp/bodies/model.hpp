// The model structure shared by every part of the compiled core.
//
// Plain structs with named fields; arrays are views (pointers) into memory owned by Python
// (NumPy arrays kept alive by the binding layer).  Layouts are C order:
//   cable quadrature data  (n_el, n_qp[, 4]);   band matrices (2 ku + 1, n) with
//   A(i, j) = ab[(ku + i - j) * n + j]   (LAPACK general band storage, kl = ku).
#pragma once

#include <cstdint>

#include "elements/tension_law.hpp"

namespace rancf {

/// Largest number of coordinates of one line element (2 nodes x 7 for a spatial rod): what the
/// line bodies' own loops (contact, fluid, sections, inertia) gather.
inline constexpr int kMaxElementDofs = 14;

/// Largest number of coordinates of any element the assembly gathers (a shell's 4 x 12).
inline constexpr int kMaxAssemblyDofs = 48;

/// Element families; each has one kernel file and one entry in the registry (registry.cpp).
enum class ElementKind : int { cable = 0, beam = 1, rod = 2, shell = 3 };

class ShellElements;  // elements/shell.hpp

/// Elements given by a connectivity (shells, docs/derivations/shell.md sec. 8): element el's
/// coordinates are those of its nodes nodes_of[el nodes + a], node by node; none (nodes_of
/// null): a chain, element el's nodes are el and el + 1.
struct Connectivity {
  int nodes = 2;                           ///< nodes of an element
  const std::int64_t* nodes_of = nullptr;  ///< (n_el, nodes), or null: the chain
  int ku = 0;  ///< half bandwidth: dpn (largest node span of an element + 1) - 1
};

/// The shell family's elements (elements/shell.hpp), owned by the binding layer, and its
/// supports (docs/derivations/shell.md sec. 7-8): node k's model coordinates are y_k = B q_k,
/// B = node_basis[node_rot[k]] (dpn x dpn, orthogonal, row-major; node_rot[k] = -1: y_k = q_k),
/// the rows of B that a support holds marked in Supports::fixed.
struct ShellData {
  const ShellElements* elements = nullptr;
  const std::int64_t* node_rot = nullptr;  ///< (n_nodes): basis of each node, or -1
  const double* node_basis = nullptr;      ///< (n_rot, dpn, dpn)
};

/// Quadrature data of cable elements (docs/derivations/cable.md §3, §6).
struct CableData {
  int n_qp = 0;
  const double* n1 = nullptr;  ///< dS/dxi   at the Gauss points, (n_el, n_qp, 4)
  const double* n2 = nullptr;  ///< d2S/dxi2 at the Gauss points, (n_el, n_qp, 4)
  const double* gw = nullptr;  ///< Gauss weights on [0, 1], (n_qp)
  const double* s0 = nullptr;  ///< reference |r0'|^2, (n_el, n_qp)
  const double* k0 = nullptr;  ///< reference curvature, (n_el, n_qp)
  const double* j0 = nullptr;  ///< reference |r0'|, (n_el, n_qp)
  const double* qr = nullptr;  ///< spatial: eta^2 k0^2 at curved points, else 0, (n_el, n_qp)
};

/// Reference chords of co-rotational beam elements.
struct BeamData {
  const double* l0 = nullptr;  ///< reference chord length, (n_el)
  const double* d0 = nullptr;  ///< reference chord vector, (n_el, 2)
};

/// Quadrature data and nodal reference triads of spatial rod elements (docs/derivations/rod.md
/// §2-§5).
struct RodData {
  int n_qp = 0;
  const double* n1 = nullptr;    ///< dS/dxi   at the Gauss points, (n_el, n_qp, 4)
  const double* n2 = nullptr;    ///< d2S/dxi2 at the Gauss points, (n_el, n_qp, 4)
  const double* xi = nullptr;    ///< Gauss points on [0, 1], (n_qp)
  const double* gw = nullptr;    ///< Gauss weights, (n_qp)
  const double* j0 = nullptr;    ///< reference |r0'|, (n_el, n_qp)
  const double* kref = nullptr;  ///< reference material curvatures K1, K2, K3, (n_el, n_qp, 3)
  double* tref = nullptr;        ///< nodal reference tangents, (n_nodes, 3); re-referenced
  double* m1ref = nullptr;       ///< nodal reference directors, (n_nodes, 3); re-referenced
};

/// Section stiffnesses.
struct Stiffness {
  double ea = 0.0;   ///< axial stiffness E A
  double ei = 0.0;   ///< bending stiffness E I (cable, beam)
  double gj = 0.0;   ///< torsional stiffness G J (rod)
  double ei2 = 0.0;  ///< bending stiffness about m1 (rod)
  double ei3 = 0.0;  ///< bending stiffness about m2 (rod)
  /// Cable axial law: false: W = 1/2 EA eps^2 (Green-Lagrange eps); true: W = 1/2 EA (lambda -
  /// 1)^2, the engineering strain of mooring codes (docs/derivations/cable.md section 6).
  bool engineering = false;
  /// Kelvin-Voigt strain-rate damping (docs/derivations/strain-rate-damping.md): N = EA eps + c_a
  /// deps/dt [N s], M = EI kappa + c_b dkappa/dt [N m^2 s], rods' twist c_t [N m^2 s]; 0: none.
  double damping_axial = 0.0;
  double damping_bending = 0.0;
  double damping_torsion = 0.0;
  /// Nonlinear axial law (cables, rods): the tension T(e) of the engineering strain replaces
  /// EA e in the axial energy, W = J0 int_0^e T (docs/derivations/axial-law.md); none: EA.
  TensionTable axial_law{};
  [[nodiscard]] bool strain_rate_damping() const {
    return damping_axial > 0.0 || damping_bending > 0.0 || damping_torsion > 0.0;
  }
};

/// Rotary inertia of rod sections per length (configuration dependent: inertia.hpp).
struct SectionInertia {
  double polar = 0.0;  ///< rho (I2 + I3): spin about the tangent
  double bend = 0.0;   ///< rho I of both bending directions ("full"; 0 for "torsion")
};

/// Supports: fixed model coordinates and the rotated blocks of supported nodes (q = T y): a
/// roller's position block into (axis, normals), a clamp's gradient block into (t0, normals).
struct Supports {
  const std::uint8_t* fixed = nullptr;        ///< (n): 1 where the coordinate is held
  const std::int64_t* rot_of_node = nullptr;  ///< (n_nodes, 2): [position, gradient] -> rot, or -1
  const double* rot = nullptr;                ///< (n_rot, dim, dim): basis columns
};

/// External loads: constant gravity forces and nodal point forces F0 [sin(2 pi f t)].
struct Loads {
  const double* f_gravity = nullptr;  ///< (n), model coordinates
  int n_point = 0;
  const std::int64_t* base = nullptr;         ///< (n_point): index of the node's first coordinate
  const double* f0 = nullptr;                 ///< (n_point, dim)
  const double* freq = nullptr;               ///< (n_point): Hz, 0 for a constant force
  int n_moment = 0;                           ///< rod only: point moments M0 [sin(2 pi f t)]
  const std::int64_t* moment_node = nullptr;  ///< (n_moment): node index
  const double* moment = nullptr;             ///< (n_moment, 3)
  const double* moment_freq = nullptr;        ///< (n_moment): Hz, 0 for a constant moment
};

/// Largest window of model coordinates that one element's (or node's) coordinates depend on
/// (reduced coordinates: continuity.py).
inline constexpr int kMaxWindow = 24;

/// Reduced coordinates (C2 meshes, rancf.mesh.continuity): the model coordinates y (n_y of
/// them: spline control points, the nodal vectors of supported nodes, rod twists) map linearly
/// to the nodal coordinates q.  Element el's coordinates are E_el y[el_start .. + width), node
/// k's (dpn of them) N_k y[node_start .. + node_width), with E and N dense row-major.  n_y == 0:
/// none (y holds the nodal coordinates node by node, clamp blocks rotated: Supports).
struct Reduction {
  int n_y = 0;
  int ku = 0;                              ///< half bandwidth of the assembled matrices
  int width = 0;                           ///< element window
  const std::int64_t* el_start = nullptr;  ///< (n_el)
  const double* el_map = nullptr;          ///< (n_el, nde, width)
  int node_width = 0;
  const std::int64_t* node_start = nullptr;  ///< (n_nodes)
  const double* node_map = nullptr;          ///< (n_nodes, dpn, node_width)
  const std::int64_t* twist = nullptr;       ///< rods: (n_nodes) index of each node's twist in y
};

/// An assembled model as the compiled core sees it.
struct Model {
  ElementKind kind = ElementKind::cable;
  int dim = 2;  ///< space dimension (2 or 3)
  int dpn = 4;  ///< coordinates per node
  int n_el = 0;
  int n_nodes = 0;
  bool closed = false;  ///< a ring: the last node is the first (rereference keeps them equal)
  Stiffness stiffness;
  SectionInertia rotary;  ///< rods: rotary inertia (not in mass_band)
  CableData cable;
  BeamData beam;
  RodData rod;
  ShellData shell;
  Connectivity connectivity;
  Supports supports;
  Reduction reduction;
  Loads loads;
  const double* mass_band = nullptr;  ///< constant mass matrix, band storage (2 ku + 1, n); rods:
                                      ///< translation only (the rotary part: inertia.hpp)
  const double* y_ref = nullptr;      ///< reference configuration, model coordinates (n)

  [[nodiscard]] bool reduced() const { return reduction.n_y > 0; }
  [[nodiscard]] int n() const { return reduced() ? reduction.n_y : n_nodes * dpn; }
  [[nodiscard]] int nde() const { return connectivity.nodes * dpn; }
  [[nodiscard]] int ku() const {
    if (reduced()) return reduction.ku;
    return connectivity.nodes_of != nullptr ? connectivity.ku : 2 * dpn - 1;
  }
};

}  // namespace rancf
