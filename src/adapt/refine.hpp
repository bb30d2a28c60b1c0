#pragma once
// Node generation for AGRS, method B (thesis 3.2.3, Fig. 3.5b): a parent cell of spacing h splits
// into 2^dim children at the centres of its sub-cells (spacing h/2, volume V/2^dim); the parent is
// deactivated and keeps its slot, so node ids stay stable. With adapt.fill_boundary_cells, where a
// hole, a clipped body or a rotated lattice leaves a neighbouring cell without a node, its
// sub-cells inside the body join as fillers, so that a refined zone has the fine grid's boundary. Children get their horizon from the
// scaling mode, micromodulus and critical stretch from their horizon (thesis Eqs. 2.13, 2.15,
// 2.21), and u, v, a from a linear fit over the parent's visible family (intact bonds only, so
// no field is carried across a crack), anchored at the parent's values: the children's mean
// equals the parent's value, which conserves linear momentum exactly.
//
// Families are then rebuilt. Bonds keep their broken state where both ends survive; new bonds
// that cross a pre-crack or the facet of a bond broken before the event start broken, so cracks
// do not heal on refinement.
#include <array>
#include <cstdint>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "model/model.hpp"

namespace periadapt {

struct RefineStats {
  std::size_t parents = 0;
  std::size_t children = 0;
  std::size_t reanchored = 0;  // children interpolated from a node other than their parent
  std::size_t fillers = 0;     // children in empty cells next to their parent (curved surfaces)
  std::array<double, 3> momentum_before{0, 0, 0};
  std::array<double, 3> momentum_after{0, 0, 0};
  double kinetic_before = 0, kinetic_after = 0;
  double momentum_scale = 0;  // sum of m |v| before the event
  double seconds = 0;  // wall time (set again by the Adaptor to include the solver refresh)
  std::vector<std::uint32_t> rebuilt;  // nodes whose families were searched again
};

// Base horizon of a node of `level` (before any interface correction).
double level_horizon(const Model& m, const AdaptSpec& spec, int level);

// What multiplies the analytic micromodulus of a node whose level has m = delta/dx = `m_level`:
// 1, or with lattice calibration the inverse of the quadrature's bulk lattice moment there.
double micromodulus_factor(const Model& m, double m_level);

// micromodulus_factor of every level 0 ... spec.max_level (all 1 without lattice calibration).
std::vector<double> level_micromodulus_factors(const Model& m, const AdaptSpec& spec);

// Sets micromodulus and critical stretch of node i from its current horizon; `factor` from
// micromodulus_factor at the m of the node's level (an interface horizon keeps its level's).
// `failure_horizon` > 0: the critical stretch is the one of that horizon instead.
void scale_material_to_horizon(Model& m, std::size_t i, double factor = 1.0,
                               double failure_horizon = 0.0);

// The horizon node i's critical stretch belongs to: its level's where an interface horizon
// widened it and spec.interface_level_stretch keeps the level's critical stretch.
double failure_horizon(const Model& m, const AdaptSpec& spec, std::size_t i);

// `inherit_boundary`: children of loaded or constrained parents join the parent's loads (same
// force density, so the same total force) and prescribed motions (used by the initial refinement;
// during a run such nodes are never refined).
RefineStats refine_nodes(Model& m, std::vector<std::uint32_t> parents, const AdaptSpec& spec,
                         bool inherit_boundary = false);

// Refines the deck's initial regions level by level before the run (AGRS machinery applied to a
// fixed zone, e.g. thesis 4.1 and 4.2), with the visibility criterion at every level.
void apply_initial_refinement(Model& m, const AdaptSpec& spec);

}  // namespace periadapt
