#pragma once
// Zones the automatic profile refines before the run, where the coarse grid is known to be wrong
// from t = 0 on (docs/agrs.md, "Zones refined at set-up").
// - adapt.refine_crack_tips: the fronts of the deck's pre-cracks. A front is a stress
//   singularity; the stretch trigger refines it only once its coarse bonds near failure, and a
//   zone made then starts from the coarse field and sheds the difference as waves at the most
//   loaded place of the body (the suite's double-edge-notched plate broke 12.5% early; with the
//   zone made at set-up, 0.4% early).
// - adapt.refine_motions: regions driven by a prescribed motion (a velocity, or a displacement
//   that changes in time) that are small against a horizon. The force such a patch puts in
//   depends on the grid under it (the suite's three-point bending beam: 18.1 kN on the coarse
//   grid against 25.6 kN on the fine one at the same displacement), so a coarse patch loads the
//   body more softly than the fine grid. The grid's share of that force is a layer about one
//   horizon wide at the region's edge: a region that holds a whole family (a node all of whose
//   bonds end inside it) carries the fine grid's force on the coarse grid (driven disks in the
//   compact-tension deck, coarse against fine: radius 1.5 mm 0.52-0.82, 2 mm 0.81-0.97, 3-6 mm
//   0.89-1.09 with a 3 mm coarse horizon; docs/agrs.md) and stays coarse.
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "core/expression.hpp"
#include "model/model.hpp"

namespace periadapt {

// One ball (2D: disk) of one coarse horizon per front point: a segment's end, or points one
// spacing apart along a quadrilateral's edge, where the body goes on beyond the crack (a node
// within 0.9 spacings of the point one spacing further out in the crack's plane); the mouth of
// a notch cut from a free surface has none. Each asks for `level`.
std::vector<InitialRefinement> crack_tip_zones(const Model& m, int level);

// The region of every prescribed motion that moves (a velocity component not identically zero,
// or a displacement component that depends on t) and whose nodes hold no whole family (see
// above), asking for `level`.
std::vector<InitialRefinement> driven_patch_zones(const Model& m, int level);

// Whether one component of a prescribed motion drives the body: a velocity not identically zero,
// or a displacement that changes in time.
bool component_moves(bool velocity, const Expression& component);

// The deck's own initial zones and those of the options above that `spec` enables (inside
// spec.region; none with a start time).
std::vector<InitialRefinement> setup_zones(const Model& m, const AdaptSpec& spec);

}  // namespace periadapt
