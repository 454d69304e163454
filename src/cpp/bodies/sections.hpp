// Strains and curvatures at sample points along every element (section outputs).
//
// The values are those the element kernels use in the strain energy, at points given by the
// caller (shape-function derivatives and reference data at the sample parameters xi):
//   cable  [eps, kappa]            eps Green-Lagrange, kappa signed (2D) / magnitude (3D)
//   beam   [eps, kappa(xi)]        co-rotational: kappa = [(6 xi - 4) tb1 + (6 xi - 2) tb2] / L0
//   rod    [eps, K1, K2, K3]       material curvatures (docs/derivations/rod.md section 4) with the
//   live triads
#pragma once

#include "bodies/model.hpp"

namespace rancf {

/// Sample points of every element: n per element; xi (n); n1, n2 (n_el, n, 4) shape-function
/// derivatives (cable, rod); s0 = |r0'|^2 (cable) or j0 = |r0'| (rod), (n_el, n).
struct SamplePoints {
  int n = 0;
  const double* xi = nullptr;
  const double* n1 = nullptr;
  const double* n2 = nullptr;
  const double* ref = nullptr;
};

/// The section values of element el (coordinates e) at the sample points p into the element's
/// rows of out (n_el, p.n, width), one function a family (its ElementKernel::section).
void section_cable(const Model& m, const SamplePoints& p, int el, const double* e, double* out);
void section_beam(const Model& m, const SamplePoints& p, int el, const double* e, double* out);
void section_rod(const Model& m, const SamplePoints& p, int el, const double* e, double* out);

/// Beam element el: [eps, kappa(xi)] at the n points xi into out (n, 2) (beam.cpp).
void beam_section(const Model& m, int el, const double* e, const double* xi, int n, double* out);

/// Values per point: 2 (cable, beam) or 4 (rod).
int section_width(const Model& m);

/// out (n_el, n, section_width) at configuration y (model coordinates).
void section_strains(const Model& m, const SamplePoints& p, const double* y, double* out);

/// The section values of a cable (w = 2) or rod (w = 4) from its strains and curvatures
/// raw (k, n_points, w) (section_outputs.py, docs/derivations/cable.md section 6): per point
/// [eps, N, kappa (w - 1), M (w - 1)] into out (k, n_points, 2 w), with
/// lambda = sqrt(max(1 + 2 eps, 0)), M_i = c_i (kappa_i - kappa0_i / scale_k) / lambda and
/// N = ea (engineering ? lambda - 1 : eps lambda) - sum_i M_i kappa_i; kappa0 (n_points, w - 1)
/// the stress-free curvatures, scale (k) the unstretched length over the reference's per state.
/// With an axial law (law.active()) the axial part is its tension T(lambda - 1) instead
/// (docs/derivations/axial-law.md).
void section_forces(int k, int n_points, int w, const double* raw, const double* kappa0,
                    const double* c, double ea, bool engineering, const TensionTable& law,
                    const double* scale, double* out);

}  // namespace rancf
