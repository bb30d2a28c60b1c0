#pragma once
// What adaptive grid refinement and scaling (AGRS) does during a run (deck section `adapt`).
#include <optional>
#include <vector>

#include "core/geometry.hpp"

namespace periadapt {

// How the horizon follows the spacing from one level to the next (thesis 2.3, F-10).
enum class HorizonScaling {
  Delta,   // delta-convergence: delta halves with the spacing, m fixed
  M,       // m-convergence: delta fixed, m doubles
  DeltaM,  // delta m-convergence: m per level from `m_per_level`, delta = m_l dX_l
};

// A zone refined before the run to a fixed level.
struct InitialRefinement {
  Shape region;
  int level = 1;
  std::optional<Shape> within;  // refined only inside this too (the profile's zones: adapt.region)
  bool widen = true;  // widened by the visibility criterion (adapt.visibility)
};

// Node generation (thesis 3.2.3, Fig. 3.5).
enum class NodeGeneration {
  B,  // children at the centres of the 2^dim sub-cells, parent removed
  A,  // 3^dim lattice at half spacing around the parent (mid-points), parent kept; coarse
      // interface cells lose the area the new cells cover (Eq. 3.4)
};

// beta of the stretch trigger when a deck names no trigger: a node is refined once a bond reaches
// half the critical stretch of its children. At a smooth stress raiser both grids see the same
// stretch, so that is half the load that breaks the finer grid there; ahead of a crack the
// largest stretch scales as delta^(-1/2) like s0 (the K field sampled over a horizon), so it is
// 1/sqrt(2) of the critical stress intensity for each level of refinement (delta-scaling).
inline constexpr double kDefaultStretchTrigger = 0.5;
// The automatic profile's stretch_reach (coarse horizons): where a K field at its critical value
// passes kDefaultStretchTrigger of the children's s0, (1 / 0.5)^2 fine = 2 coarse horizons ahead.
inline constexpr double kDefaultStretchReach = 2.0;

struct AdaptSpec {
  bool enabled = false;
  // solver.allow_unstable_time_step: an event that leaves the step above the refined rows' bound
  // goes on (the divergence check stops the run if it blows up) instead of stopping it.
  bool allow_unstable_step = false;
  NodeGeneration method = NodeGeneration::B;
  std::vector<InitialRefinement> initial;  // refined at t = 0
  // Refined to max_level at t = 0 (adapt/setup_zones.hpp): the fronts of the deck's pre-cracks,
  // and the regions driven by prescribed motions.
  bool refine_crack_tips = false;
  bool refine_motions = false;
  bool visibility = true;                  // initial zones widened by the visibility criterion
  int max_level = 1;
  HorizonScaling scaling = HorizonScaling::Delta;
  std::vector<double> m_per_level;  // DeltaM: m of levels 0, 1, ... (at least max_level + 1)
  bool interface_horizon = false;   // thesis 3.2.3: interface nodes get m x distance to coarse
  // With interface_horizon: an interface node's critical stretch stays its level's (true), or
  // follows its widened horizon as in the thesis (F-14; false), which makes it fail below the
  // strain its neighbours of the same level hold.
  bool interface_level_stretch = true;
  // Interface rows' bond factors fitted so that a uniform strain pulls no node (patch test;
  // discretize/interface_quadrature.hpp). Bond-based forces only.
  bool interface_fit = false;
  // Method B: where a hole, a clipped body or a rotated lattice leaves a neighbouring cell of a
  // parent without a node, its sub-cells inside the body join as children too, and the children
  // of such boundary parents take a fine cell's volume: a refined zone gets the fine grid's
  // boundary rather than the coarse staircase (docs/agrs.md, "Refined zones at curved
  // boundaries").
  bool fill_boundary_cells = false;
  // Interface rows' ghost forces removed to first order in the local strain
  // (solver/ghost_correction.hpp). Source-horizon pairing, PMB and LPS.
  bool ghost_correction = false;
  double start_time = 0.0;          // t_st: no refinement before
  int check_every = 1;              // steps between energy-trigger checks
  std::optional<double> energy_fraction;  // energy trigger W >= alpha W_max (None: off)
  // stretch trigger: an intact bond at >= beta x the s0 of the node's children (one level finer) (None: off)
  std::optional<double> stretch_fraction;
  bool damage_trigger = false;            // damage trigger: delta phi > 0, step redone
  // Once a bond has broken in a step, the stretch trigger refines only nodes within this many of
  // their horizons of a cracked node (triggers.hpp, near_cracks); 0: everywhere. Needs the damage
  // trigger, which then refines what breaks farther away.
  double stretch_reach = 0.0;
  std::optional<Shape> region;            // refinement allowed only inside
  bool total_energy = false;              // trigger on W + kinetic energy density (Bobaru)
  bool coarsen = false;                   // return quiet refined zones to their parents
  double visibility_factor = 1.0;         // visibility radius in horizons of the flagged node
  bool conserve_energy = false;           // rescale rebuilt rows' velocities so events keep K + U
  int relax_sweeps = 0;  // Jacobi sweeps relaxing each event's rebuilt rows (adapt/event_relaxation.hpp)
  bool relax_until_crack = false;  // relax only the events before a step has broken a bond
  // Loaded nodes are refined with the nodes bonded to them, their children carrying the load
  // (method B; off: loaded nodes are never refined, thesis MSc 2.1).
  bool refine_loads = false;
};

}  // namespace periadapt
