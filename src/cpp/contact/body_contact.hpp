// Contact between flexible bodies and self-contact: penalty contact of tubes, segment
// against segment, with regularized Coulomb friction (as contact.hpp's) where the pair has it.
//
// Every contact point x_i (the Gauss points of contact.hpp, weight w_i: the integral over the
// reference arc length) of body A is projected on every element f of body B that the broad
// phase finds near it: y(xi*) = sum_k N_k(xi*) e_k with xi* minimizing |x_i - y(xi)| over
// [0, 1] (Newton on (y - x) . y' = 0 from the best of five samples; at a step's end from the
// alpha point's xi*).  The gap is
//   g = |x_i - y(xi*)| - r_A - r_B,   n = (x_i - y) / |x_i - y|,
// and the energy w_i Phi(g) / 2 with the penalty of contact_law.hpp (in a time step the
// pressure is its mean over the gaps [2 gs - g(y1), g(y1)], gs the step's gap, as contact.hpp's); A
// against B and B against A both count (hence the half), so the pair is symmetric.  A projection is
// kept where xi* is inside the element, or at a free end of B (else the neighbouring element holds
// the closest point).  Self-contact ignores points less than pi (r_A + r_B) of reference arc length
// apart along the body (a tube bent no tighter than its radius cannot touch itself there).  Since g
// is stationary in xi*, its gradient is n . (dx - N(xi*) de_f), so the forces are the exact
// gradient of the energy: p w_i n on x_i, -p w_i n at y(xi*) (p = -Phi'(g) / 2 ... as
// contact_law.hpp's p with stiffness k / 2).
//
// Broad phase: a bounding sphere per element (its nodes and contact points, enlarged by a
// tenth of its chord for the curve between them, and the tube radius) in a uniform grid of
// cells as large as the largest sphere (hash map of cells): pairs of elements in the same or
// neighbouring cells whose spheres overlap; cost near linear in the number of elements.  The
// forces of a time step take their points from a list of near points kept between assemblies
// (body_broad.hpp update_near: made again when an element has moved by a margin), each
// projection started from the point's last closest point, and a point whose kept lower bound
// of its gap (body_broad.hpp) shows it clear of the element within the step not projected.
//
// Tangent: exact, from the gap's Hessian including the projection's variation
// (body_contact.cpp pair_geometry) and, with friction, the slip's variation with the normal,
// the closest point and the velocities (body_contact.cpp friction); the element pairs'
// tangents are summed by node blocks (a node pair's block once, whichever element pairs and
// orders give it), which then go through the sink (couplings of distant elements: the
// bordered solve's far entries).
#pragma once

#include "contact/contact.hpp"
#include "linalg/bordered.hpp"
#include "system/system.hpp"

namespace rancf {

/// Forces of the body pairs at (yf, vf) into r (r -= generalized forces) with the step's mean
/// pressure up to y1 (null: statics, the pressure at yf; contact.hpp) and, where the pair has
/// friction and vf is given, the regularized Coulomb friction of contact.hpp on the slip
/// velocity relative to the other body's material point; their Jacobian with respect to y1
/// (ck d/dyf + cv d/dvf + c1 d/dy1, AssemblyTerms) into add (if not null).
void assemble_body_contact(const System& s, const ContactSet& c, const double* yf, const double* vf,
                           const double* y1, const AssemblyTerms& tm, double* r,
                           const MatrixSink* add);

/// The penalty energy of the body pairs at y.
double body_contact_energy(const System& s, const ContactSet& c, const double* y);

/// Values per body pair at y (kBodyOutputs each): the smallest gap among the broad phase's
/// candidates (1e300 if none), the number of points in contact, and the total normal force
/// (sum of p w_i over both directions).
inline constexpr int kBodyOutputs = 3;
void body_contact_outputs(const System& s, const ContactSet& c, const double* y, double* out);

}  // namespace rancf
