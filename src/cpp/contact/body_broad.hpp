// The broad phase of contact between flexible bodies (body_contact.hpp): a bounding sphere per
// element (its nodes and contact points, enlarged by a tenth of its chord for the curve between
// them, the tube radius, and twice a time step's motion of its nodes) and, per body pair, the
// element pairs whose spheres overlap, found through a uniform grid of cells as large as the
// largest sphere (a hash map of cells): near linear in the number of elements.  A capsule
// about each element's chord with the same margins then sorts out single points (an element's
// neighbours along a body overlap its sphere, but most of their points are far from it).
//
// The near points (update_near, for the forces and tangents of a time step's Newton
// iterations): an element's curve is a rational cubic Bezier curve with positive weights,
// y = sum_i R_i P_i (R_i >= 0, sum R_i = 1; P0 = r0, P1 = r0 + c1 r0', P2 = r1 + c3 r1',
// P3 = r1 with cable_shape's c1, c3), so it lies in the convex hull of its control points P_i
// and moves by at most the largest motion of its control points.  A point x of element e is
// kept against element f if the distance bound of x from f's hull (or, in self-contact, from
// the hull of f's part outside the excluded arc, de Casteljau's subdivision) is within the
// tubes' radii, the onset and a margin delta.  The list stays valid while
//   2 (max |P - P_list| + m) < delta,  m = max |P(y1) - P(y)| (times (1 - af) / af where the
//   step's gaps blend those at its start y0 = (y - (1 - af) y1) / af and end, af < 1/2):
// a point it left out was farther than r_A + r_B + onset + delta from f when it was made, so
// its gap stays above the onset at y and at the step's start and end (the gap is 1-Lipschitz
// in the points' motion).  delta = max(r_A + r_B, 4 m).  The closest point found at
// the last assembly is kept per point and starts the next projection (Newton from it).
// Each point also keeps a lower bound of its gap to f (its gap at its last projection, or
// the hull's bound where it was not projected) and the sum of e's and f's drifts then (an
// element's drift: the largest motion of its control points from one assembly to the next,
// summed over the assemblies): the gap is 1-Lipschitz in the motion of x (a convex
// combination of e's control points) and of f's curve, so it is at least that bound less
// the drifts since.  A point whose bound exceeds e's and f's motion in the step cannot
// touch f within it and is not projected (body_contact.cpp each_near).
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "contact/contact.hpp"
#include "system/system.hpp"

namespace rancf {

/// A bounding sphere per element of every flexible body with contact curves.
struct Broad {
  std::vector<std::array<double, 4>> sphere;  ///< centre (3), radius incl. the tube
  std::vector<double> moved;                  ///< twice a step's motion of its nodes
  /// a capsule per element: its chord (ends, 6) and a radius as the sphere's (the farthest of
  /// its nodes and contact points from the chord instead of from their centre)
  std::vector<std::array<double, 7>> capsule;
  std::vector<int> start;  ///< first sphere of each flexible body
};

/// The distance of x from the segment seg = (a (3), b (3)).
double to_segment(const double* seg, const double* x);

/// The spheres at y (y1 not null: a step's end too).
Broad spheres(const System& s, const ContactSet& c, const double* y, const double* y1);

/// Candidate (element of bp.a, element of bp.b) pairs whose spheres overlap (with the onset).
std::vector<std::pair<int, int>> candidates(const Broad& br, const BodyPair& bp);

/// The reference arc length of point q of element e along its body (the points' quadrature).
double point_arc(const ContactBody& cb, int e, int q);

/// Self-contact ignores points less than this reference arc length apart (body_contact.hpp).
double excluded_arc(const ContactBody& a, const ContactBody& b);

/// Self-contact: the part [lo, hi] of element f (of body cb) at least excluded_arc away along
/// the body from point q of element e (another element of it); false if f has none.
bool outside_window(const ContactBody& cb, int e, int q, int f, double& lo, double& hi);

/// The control points P (4 x 3) of element el's curve at its coordinates x (body_broad.cpp).
void control_points(const Model& m, const ContactBody& cb, int el, const double* x, double (*P)[3]);

/// A lower bound of the distance from x to the part [lo, hi] of element el's curve (control
/// points P; body_broad.cpp), -1 if none is known.
double hull_distance(const ContactBody& cb, int el, const double (*P)[3], const double* x,
                     double lo, double hi);

/// Make nl valid at (y, y1) (y1 null: statics): kept if no element's control point has moved
/// since it was made by half its margin less the largest motion in the step (y to y1), else
/// made again (body_broad.cpp).  Returns whether it was made again.
bool update_near(const System& s, const ContactSet& c, const double* y, const double* y1,
                 NearList& nl);

}  // namespace rancf
