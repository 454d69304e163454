// Rod-specific operations beyond the element kernel (see rod.cpp).
#pragma once

#include "bodies/model.hpp"

namespace rancf {

/// Material curvatures k (n_qp, 3) and axial strains eps (n_qp) of element el, coordinates e (q).
void rod_curvatures(const Model& m, int el, const double* e, double* k, double* eps);

/// Axial strain and material curvatures at n points of element el (coordinates e, q), out
/// (n, 4) = [eps, K1, K2, K3], with the model's current nodal triads; n1, n2 (n, 4) and j0 (n)
/// at the points xi (n).
void rod_point_strains(const Model& m, int el, const double* e, int n, const double* xi,
                       const double* n1, const double* n2, const double* j0, double* out);

/// Nodal triad: t = rx/|rx|, m1 = cos(phi) u + sin(phi) t x u, u = SR(tref -> t) m1ref.
void rod_nodal_triad(const double* tref, const double* m1ref, const double* rx, double phi,
                     double* t, double* m1);

/// Point moment at `node` with gradient rx: generalized force g (4: on r_x, then phi) and, if kl
/// is not null, its derivative kl (4 x 4, row-major) with respect to (r_x, phi).
void rod_moment_load(const Model& m, int node, const double* moment, const double* rx, double* g,
                     double* kl);

/// Rotary inertia of element el (rod_inertia.hpp, docs/derivations/rod-kernel.md §11): inertial
/// force fe (14) at e, ed, edd (q coordinates) and, if ke, ck dF/de + cv dF/ded + ca dF/dedd (14 x
/// 14); damping: mass-proportional coefficient c (force c dT/ded).
void rod_inertia(const Model& m, int el, const double* e, const double* ed, const double* edd,
                 double damping, double ck, double cv, double ca, double* fe, double* ke);

/// Rotary kinetic energy of element el (§11.1); `current` as in rod_rotary_momentum.
double rod_rotary_energy(const Model& m, int el, const double* e, const double* ed, bool current);

/// Rotary angular momentum of element el added to out (3); with `current` the nodal references
/// are the current tangents (the spin is then read from the twist rates: a re-referenced state).
void rod_rotary_momentum(const Model& m, int el, const double* e, const double* ed, bool current,
                         double* out);

/// Twist rate and acceleration of `node` kept physical when its triad is re-referenced (§11.6).
void rod_rereference_rates(const Model& m, int node, const double* rx, const double* rxd,
                           const double* rxdd, double& phid, double& phidd);

}  // namespace rancf
