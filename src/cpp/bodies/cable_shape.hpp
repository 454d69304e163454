// The scalar RANCF cable shape functions at a parameter xi: the one C++ copy of
// rancf.elements.cable.cable_shape_functions (docs/derivations/cable.md sec. 3), for the
// kernels that evaluate an element at run-time parameters (sliding joints, body contact).
#pragma once

namespace rancf {

/// N = [R0 + R1, c1 R1, R2 + R3, c3 R2] at xi and its first and second xi-derivatives (4
/// values each; n1, n2 may be null), R_i = w_i B_i / sum_j w_j B_j the rational cubic
/// Bernstein basis of the element's weights w (4), c1 = l w0 / (3 w1), c3 = -l w3 / (3 w2), l
/// its gradient scale.
void cable_shape(const double* w, double l, double xi, double* n0, double* n1, double* n2);

}  // namespace rancf
