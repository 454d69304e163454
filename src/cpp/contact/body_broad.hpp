// The broad phase of contact between flexible bodies (body_contact.hpp): a bounding sphere per
// element (its nodes and contact points, enlarged by a tenth of its chord for the curve between
// them, the tube radius, and twice a time step's motion of its nodes) and, per body pair, the
// element pairs whose spheres overlap, found through a uniform grid of cells as large as the
// largest sphere (a hash map of cells): near linear in the number of elements.  A capsule
// about each element's chord with the same margins then sorts out single points (an element's
// neighbours along a body overlap its sphere, but most of their points are far from it).
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

}  // namespace rancf
