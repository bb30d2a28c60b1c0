#pragma once
// Steps shared by the two node-generation methods of AGRS (refine.cpp: method B, children at
// sub-cell centres, parent removed; refine_method_a.cpp: method A, mid-points, parent kept).
#include <chrono>
#include <cstdint>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "adapt/crack_memory.hpp"
#include "adapt/refine.hpp"
#include "model/model.hpp"

namespace periadapt {

// The opening of an event: parents sorted and unique, momentum and kinetic energy before, and
// the parent flags over the current nodes (empty when there is nothing to refine). With held
// bond rows, every rank gets the parents' rows and their neighbours' (collective).
std::vector<char> begin_refinement(Model& m, std::vector<std::uint32_t>& parents, RefineStats& st);

// A new node may go at `pos` (spacing h): inside the body box and a disk body, outside holes.
bool inside_body(const Model& m, const Vec3& pos, double h);

// Gradients of u, v and a at node p over its visible family: G[field][component][direction].
void fit_kinematic_gradients(const NodeSet& ns, const BondFamilies& bf, std::uint32_t p,
                             double G[3][3][3]);

// True when the straight line from a to b crosses a pre-crack or one of the facets standing for
// the broken bonds of the nodes an event removes: a node at b cannot take its field from a.
bool sight_blocked(const Model& m, const CrackMemory& memory, const Vec3& a, const Vec3& b);

// u, v and a of a new node at `pos` created from parent p (gradients G): the parent's values
// plus G times `offset` when the node can see its parent; otherwise (the node lies across a crack
// from it) the values of the nearest old node of the parent's family that it can see, plus that
// node's own gradient times the distance to it (the mean over the nearest ones where several
// are equally near). Returns true in the second case. Reads only
// nodes that are still active, so call it before any parent is switched off.
bool interpolate_new_node(const Model& m, const CrackMemory& memory, std::uint32_t p,
                          const double G[3][3][3], const double offset[3], const Vec3& pos,
                          double u[3], double v[3], double a[3]);

// u, v and a at `pos` from the nearest of `candidates` that are active and can see it: each one's
// values plus its own gradient times the distance to it, averaged over those equally near (to
// round-off; on a lattice several often are, and mirror-image nodes must get mirror-image
// fields). Returns false, leaving u, v, a at zero, when none can see it.
bool extrapolate_from_nearest_visible(const Model& m, const CrackMemory& memory,
                                      const std::vector<std::uint32_t>& candidates, const Vec3& pos,
                                      double u[3], double v[3], double a[3]);

// Initial refinement: nodes created from a loaded or constrained parent (ns.parent, ids >= n0)
// join its loads and, when inside the motion's region, its prescribed motions. A refined parent
// stays in the lists only when it survives (method A).
void inherit_loads_and_motions(Model& m, std::size_t n0, const std::vector<char>& is_parent,
                               bool parents_survive);

// Method A (refine_method_a.cpp); refine_nodes dispatches to it.
RefineStats refine_nodes_method_a(Model& m, std::vector<std::uint32_t> parents,
                                  const AdaptSpec& spec, bool inherit_boundary);

// The common tail of an event: interface-horizon correction, local family rebuild around the
// changed nodes (`changed`: refined parents and nodes whose volume changed; new nodes and nodes
// whose horizon changes here are added), momentum and kinetic energy after, wall time since t0.
void finish_refinement(Model& m, const AdaptSpec& spec, const CrackMemory& memory, std::size_t n0,
                       std::vector<char> changed, std::chrono::steady_clock::time_point t0,
                       RefineStats& st);

}  // namespace periadapt
