// Assembly over the element chain: forces, tangents and energy in model coordinates.
//
// Model coordinates y relate to the nodal coordinates q by q = T y, T block diagonal: identity
// except for the gradient blocks of clamped nodes, which are rotated into the basis of their
// reference tangent (rot).  Element data are gathered in q, the element kernel is called, and
// forces and tangents are mapped back (f_y = T^T f_q, K_y = T^T K_q T).
#pragma once

#include "bodies/model.hpp"
#include "linalg/band.hpp"

namespace rancf {

/// Element coordinates e (model coordinates y) to full nodal coordinates q: the gradient blocks
/// of clamped nodes rotated (e <- T e); only needed where has_rotation(m, el).
void rotate_to_q(const Model& m, int el, double* e);

/// Element force and matrix back to model coordinates: fe <- T^T fe, ke <- T^T ke T (ke may be
/// null).
void rotate_back(const Model& m, int el, double* fe, double* ke);

/// True if one of the element's nodes has a clamp rotation.
bool has_rotation(const Model& m, int el);

/// Element coordinates e (2 dpn values, full nodal coordinates q) of element el from a vector x
/// in model coordinates (y, v or a): the rotated blocks undone, or the reduction's map applied;
/// zeros if x is null.
void gather_element(const Model& m, int el, const double* x, double* e);

/// Add an element's force fe (q) into f (model coordinates) and, if k and ke are not null,
/// k_scale times its matrix ke (q, nde x nde) into the band k: f += T^T fe, K += T^T ke T.
void scatter_element(const Model& m, int el, const double* fe, const double* ke, double* f,
                     const BandView* k, double k_scale);

/// Reduced models: f += N^T g, a generalized force g on one node's full coordinates (dpn values)
/// into the model coordinates through the node's map.
void scatter_node(const Model& m, int node, const double* g, double* f);

/// Index in y of a rod node's twist.
int twist_index(const Model& m, int node);

/// An element's terms: its force fe (nde values, full nodal coordinates q) and, if ke is not
/// null, its matrix ke (row-major, nde x nde); fe and ke hold max(nde, kMaxElementDofs) and its
/// square values; ctx is the caller's.
using ElementTerms = void (*)(const void* ctx, int el, double* fe, double* ke);

/// Every element's terms added into f and, if k is not null, k_scale times their matrices into
/// the band k (scatter_element), computed on assembly_threads() threads and added in element
/// order, so the sums are those of one thread bit for bit (bodies/threads.hpp).  False
/// (nothing done) where the loop is not shared: fewer than kMinParallelElements elements, one
/// thread, or the pool busy; the caller then runs its own loop.
bool add_elements_shared(const Model& m, ElementTerms terms, const void* ctx, double* f,
                         const BandView* k, double k_scale);

/// Internal force f (n) and, if k is not null, the tangent added into *k (scaled by k_scale).
void assemble(const Model& m, const double* y, double* f, const BandView* k, double k_scale);

/// Kelvin-Voigt strain-rate damping (docs/derivations/strain-rate-damping.md): the force f_d(y, v)
/// added into f (n) and, if k is not null, its Jacobian ck df_d/dy + cv df_d/dv added into *k.
/// Nothing for a model without it (Stiffness::strain_rate_damping).
void assemble_damping(const Model& m, const double* y, const double* v, double ck, double cv,
                      double* f, const BandView* k);

/// Total strain energy.
double strain_energy(const Model& m, const double* y);

/// External force at time t and configuration y (gravity, point forces, point moments): f (n).
/// With `amplitude`, harmonic loads count with their amplitude (statics) and t is ignored.
void external_force(const Model& m, double t, const double* y, double* f, bool amplitude = false);

/// Subtract scale * d f_ext / dy (the load stiffness of point moments) from the band matrix k.
void subtract_load_stiffness(const Model& m, double t, const double* y, const BandView& k,
                             double scale, bool amplitude = false);

/// The full nodal gradient r_x (dim values) of `node` from model coordinates y (undoes a clamp
/// rotation).
void nodal_gradient(const Model& m, const double* y, int node, double* rx);

/// Element coordinates e (2 dpn values, full nodal coordinates q) of element el from model
/// coordinates y (clamp rotations undone).
void element_coordinates(const Model& m, const double* y, int el, double* e);

/// Re-reference the rod's nodal triads at configuration y (no-op for other elements).
void rereference(const Model& m, const double* y);

}  // namespace rancf
