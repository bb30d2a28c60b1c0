#pragma once
// Refinement triggers (thesis Algorithms A.1, A.2) and the visibility criterion (Bobaru et al.
// 2009, 5.1; thesis Fig. 3.6). A node can be refined when it is active, below the maximum level,
// inside the allowed region and carries no load or prescribed motion (thesis, MSc 2.1: nodes with
// boundary conditions are never refined).
#include <cstdint>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "model/model.hpp"

namespace periadapt {

// Refinable flags for every node (see above).
std::vector<char> refinable_nodes(const Model& m, const AdaptSpec& spec);

// Energy trigger: nodes with W_i >= alpha max_j W_j (max over the active nodes without
// prescribed motion, whose boundary-layer energies would switch the trigger off) that are
// refinable or already refined: a hot refined node asks for the coarse nodes around it
// (thesis Fig. 3.4: a request of a child is mapped to the coarse nodes close to it), which is
// how the refined zone keeps ahead of a travelling wave or a running crack.
std::vector<std::uint32_t> energy_trigger(const Model& m, const std::vector<double>& W,
                                          double alpha, const std::vector<char>& refinable);

// Stretch trigger: refinable nodes with an intact breakable bond to a node of their own level or
// coarser stretched to at least beta times the critical stretch their children will have (bonds
// into a finer zone do not count: breakable_stretch.hpp). No-fail nodes have no breakable bond, so
// they never ask for refinement themselves; they join a zone only through the visibility
// criterion, where a crack-prone zone within a horizon would otherwise end at them (an interface
// there breaks the fine side's bonds: the suite's double-edge-notched plate cracked along its
// no-fail strips when they were kept coarse). Measured against the bond law's own failure point, it fires where bonds are
// on their way to breaking, not where the load happens to be largest (as W >= alpha W_max does
// while a load ramps up), and it refines ahead of a crack before any bond breaks coarse.
// With `rows`, only those are examined (a distributed run's owned rows).
std::vector<std::uint32_t> stretch_trigger(const Model& m, const AdaptSpec& spec, double beta,
                                           const std::vector<char>& refinable,
                                           const std::vector<std::uint32_t>* rows = nullptr);

// The stretch trigger's reach once the body cracks: of `ids`, those within `reach` times their own
// horizon of an active node with a broken or cut bond. Ahead of a tip at its critical load the
// stretch falls as s0 sqrt(delta / r) (the K field sampled over a horizon), so it passes half the
// children's s0, the trigger's level, out to r = 2 coarse horizons; a coarse node farther away
// sits in a smooth field, where both grids see the same stretch and the damage trigger redoes
// any step that breaks a coarse bond there refined. Without the reach a body loaded through its
// whole section refines wherever the waves of its cracks pass half the children's s0.
std::vector<std::uint32_t> near_cracks(const Model& m, const std::vector<std::uint32_t>& ids,
                                       double reach);

// Damage trigger: of the nodes whose damage grew (`damaged`), those refinable or already refined.
std::vector<std::uint32_t> damage_trigger(const Model& m, const std::vector<std::uint32_t>& damaged,
                                          const std::vector<char>& refinable);

// With spec.refine_loads: a loaded node bonded to a parent of the same or a coarser level joins
// the parents. A fine zone bonded to a coarse loaded row pulls on it with its own, larger
// micromodulus and gets only the coarse one's back (source-horizon pairing): the row then gives
// way 35% more than on the fine grid (tests/test_agrs_invisible.cpp). `only` (per node): the
// loaded nodes looked at (a rank's own rows).
void add_loaded_neighbours(const Model& m, const std::vector<char>& refinable,
                           std::vector<std::uint32_t>& parents,
                           const std::vector<char>* only = nullptr);

// Visibility: the refinable identified nodes and every refinable node j at the same or a coarser
// level within radius_factor max(delta_i, delta_j) of an identified node i (no coarse node sees
// it, whose horizon is the larger one), e.g. Bobaru's six horizons with radius_factor 6.
std::vector<std::uint32_t> apply_visibility(const Model& m, const std::vector<std::uint32_t>& ids,
                                            const std::vector<char>& refinable,
                                            double radius_factor = 1.0);

}  // namespace periadapt
