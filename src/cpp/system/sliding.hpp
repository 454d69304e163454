// Sliding joints: a flexible body runs through a place without friction
// (docs/derivations/sliding.md).
//
// Besides its multipliers lambda (dim), the joint has one more algebraic unknown, kept in the
// multiplier vector right after them (the slot joint_row + dim): the material coordinate
// sigma = e + xi of the body's point at the place (element e, its parameter xi; a closed body's
// sigma is taken modulo the elements; beyond an open body's ends the end element's polynomial
// is continued, and the outputs report it).  Its equations:
//   g = r(y, sigma) - x_B(y)              (dim rows: the body's point is at the place)
//   h = lambda . r_sigma(y, sigma)        (the slot's row: the reaction is normal to the body)
// r = sum_k N_k(xi) e_k, the element's centre line, linear in its coordinates e_k, so that
// every derivative is exact: dg/dy = [N^T, -dx_B/du], dg/dsigma = r_sigma,
// dh/dy = lambda . N'^T, dh/dlambda = r_sigma, dh/dsigma = lambda . r_sigma_sigma; the balance
// gets G^T lambda and its derivative with respect to sigma, lambda . N'^T.  Only a place on a
// rigid body turns the direction of lambda . dx_B/du (central differences, as for every joint).
#pragma once

#include <vector>

#include "contact/contact.hpp"
#include "system/places.hpp"
#include "system/system.hpp"

namespace rancf {

/// A flexible body's element geometry, for sliding joints along it.
struct SlidingBody {
  std::vector<double> weights;  ///< (n_el, 4) rational weights; empty: no sliding joint
  std::vector<double> scales;   ///< (n_el) gradient scales
  bool closed = false;          ///< a ring: sigma modulo n_el
};

struct SlidingSet {
  std::vector<SlidingBody> of_body;  ///< by flexible body
};

/// The body's point at sigma: its centre line and the derivatives with respect to the local
/// coordinates (index: the global y indices of the element's two nodes).
struct SlidePoint {
  int n = 0;
  int index[2 * kMaxLocal] = {};
  int element = 0;
  double xi = 0.0;
  double r[3] = {0.0, 0.0, 0.0};      ///< position
  double rs[3] = {0.0, 0.0, 0.0};     ///< d r / d sigma
  double rss[3] = {0.0, 0.0, 0.0};    ///< d2 r / d sigma2
  double dr[3][2 * kMaxLocal] = {};   ///< d r / d u_j
  double drs[3][2 * kMaxLocal] = {};  ///< d r_sigma / d u_j
};

/// Flexible body `body`'s point at sigma for the coordinates y.
void slide_point(const System& s, int body, const double* y, double sigma, SlidePoint& out);

/// The rows g (dim) of sliding joint jd at (y, sigma, t).
void sliding_rows(const System& s, const JointData& jd, const double* y, double t, double sigma,
                  double* g);

/// The rate of the material coordinate of every sliding joint at (y, v) (into its slot of
/// rates, m values; others untouched): the body's point moves with the place,
/// N v_e + r_sigma sigma' = dx_B/du v_B, in the least-squares sense along r_sigma.
void sliding_rates(const System& s, const double* y, const double* v, const double* lam, double t,
                   double* rates);

/// The joint's part of the balance r: G(yf)^T lambda on the bodies' rows, g(y1) on its rows,
/// h(yf) on its slot's; add (may be null): ck d(G^T lambda)/dy of a place on a rigid body.
void sliding_residual(const System& s, std::size_t k, const double* yf, const double* lam,
                      const double* y1, const AssemblyTerms& tm, double* r, const MatrixSink* add);

/// The joint's entries in the border of the Jacobian with respect to (y1, lambda, sigma).
void sliding_border(const System& s, std::size_t k, const double* yf, const double* lam,
                    const double* y1, const AssemblyTerms& tm, BorderedLU& lu);

}  // namespace rancf
