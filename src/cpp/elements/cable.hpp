// Cable element geometry at a Gauss point, shared by the kernels and the reference set-up.
#pragma once

namespace rancf {

/// Regularization eta of the spatial magnitude curvature at curved reference points.
inline constexpr double kCableEta = 0.05;
/// Below this value of kappa0 J0 a spatial reference point counts as straight.
inline constexpr double kCableStraight = 1e-12;

struct QpGeometry {
  double aa;     ///< |r'|^2
  double kappa;  ///< curvature: signed (planar) or magnitude (spatial), |r' x r''| / |r'|^3
};

/// |r'|^2 and the curvature from a = r', b = r'' (dim 2 or 3).
QpGeometry cable_qp_geometry(const double* a, const double* b, int dim);

/// Green-Lagrange axial strain relative to the reference, eps = (|r'|^2 - s0) / (2 s0), with
/// s0 = |r0'|^2 (docs/derivations/cable.md section 6); the one definition used by kernels and
/// outputs.
inline double green_lagrange(double aa, double s0) { return (aa - s0) / (2.0 * s0); }

}  // namespace rancf
