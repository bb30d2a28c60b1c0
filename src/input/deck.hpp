#pragma once
// A validated input deck: every key typed, checked and defaulted. See docs/deck-reference.md.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "input/deck_error.hpp"
#include "adapt/adapt_spec.hpp"
#include "material/contact.hpp"
#include "material/impactor.hpp"
#include "overlay/pdro.hpp"
#include "discretize/grid.hpp"
#include "discretize/partial_volume.hpp"
#include "discretize/precrack.hpp"
#include "discretize/surface_correction.hpp"
#include "material/micromodulus.hpp"
#include "model/time_function.hpp"
#include "parallel/row_partition.hpp"

namespace periadapt {

struct LoadSpec {
  enum class Kind { Traction, BodyForce } kind = Kind::Traction;
  std::string name;
  Shape region;
  DeckPlace region_at;
  Vec3 value{0, 0, 0};   // traction (Pa) or body-force density (N/m^3)
  double layer = 0.0;    // traction: depth of the loaded layer (0: one grid spacing)
  TimeFunction time;
};

struct MotionSpec {
  enum class Kind { Velocity, Displacement } kind = Kind::Velocity;
  std::string name;
  Shape region;
  DeckPlace region_at;
  std::array<std::optional<std::string>, 3> component;
  std::array<DeckPlace, 3> component_at;
};

// load_displacement.png: the force of one load or boundary condition against the mean
// displacement of its nodes, one component.
struct LoadDisplacementPlot {
  std::string name;
  int component = 0;
};

// A part of the body with its own material (deck list `blocks`).
struct BlockSpec {
  std::string name;
  Shape region;
  double E = 0, rho = 0;
  std::optional<double> nu, G0, s0;
  int line = 0, column = 0;  // of its region key (errors found when the grid exists)
};

struct NamedRegion {
  std::string name;
  Shape region;
};

struct OutputSpec {
  std::string directory = "out";
  int vtu_count = 10;                 // snapshots over the run (plus the initial state)
  long history_every = 10;            // steps between history rows and tip samples
  long checkpoint_every = 0;          // steps between checkpoints (0: only on SIGINT/SIGTERM)
  std::optional<LoadDisplacementPlot> load_displacement;
  std::vector<double> png_times;      // damage pictures at these times (end time always)
  int png_width = 1200;
  bool vtu = true;
  bool stress = false;                // stress, strain (and LPS dilatation) in the VTU
  bool vtu_zlib = false;              // zlib-compressed VTU arrays
  std::vector<NamedRegion> regions;   // sums over these in history.csv and summary.json
  // crack tip
  bool track_tip = false;
  double tip_threshold = 0.35;
  std::optional<Vec3> tip_origin, tip_direction;
  std::string tip_side = "both";
  double tip_window = 2e-6;
  std::optional<double> branch_gap;
  std::optional<double> tip_advance;  // initiation: the tip this far ahead (default: dx)
};

struct Deck {
  std::string file;
  std::string physics_text;  // the deck's YAML without output and run length (checkpoint match)
  // model
  int dim = 2;
  PlaneCondition plane = PlaneCondition::None;
  double thickness = 1.0;
  std::string formulation = "pmb";  // pmb, lps or a history law of material/bond_laws.cpp
  // material
  std::string material_name = "material";
  double E = 0, rho = 0;
  std::optional<double> nu, G0, s0;
  double thermal_strain = 0.0;  // alpha dT, subtracted from every bond stretch
  double law_stress = 0.0;      // a history law's stress key (yield_stress, peak_stress)
  InfluenceShape shape = InfluenceShape::Constant;
  // Parts with their own material; a node takes the last block whose region holds it, the
  // material above where none does.
  std::vector<BlockSpec> blocks;
  // discretization
  GridSpec grid;
  double horizon_factor = 3.0;  // m = delta / dx
  double horizon = 0.0;         // delta
  Quadrature quadrature = Quadrature::PaPdlammps;
  SurfaceCorrection surface_correction = SurfaceCorrection::None;
  bool lattice_calibration = false;  // micromodulus_calibration: lattice
  // cracks, loads, boundary conditions, initial fields
  std::vector<PreCrack> cracks;
  std::vector<LoadSpec> loads;
  std::vector<MotionSpec> motions;
  std::array<std::optional<std::string>, 3> initial_displacement, initial_velocity;
  std::array<DeckPlace, 3> initial_displacement_at, initial_velocity_at;
  // damage
  bool damage = true;
  std::vector<Shape> no_fail;
  std::vector<DeckPlace> no_fail_at;
  std::vector<DeckPlace> holes_at;  // discretization.holes[k]
  DeckPlace body_at{"discretization.body"};
  std::vector<DeckPlace> crack_at;
  DeckPlace solver_type_at{"solver.type"};
  std::vector<DeckPlace> initial_refinement_at;  // adapt.initial_refinement[k].region
  std::optional<DeckPlace> adapt_region_at;
  PdroSpec pdro;
  ContactSpec contact;
  std::vector<Impactor> impactors;
  // solver
  enum class SolverType { Explicit, Static, Relaxation } solver = SolverType::Explicit;
  int load_steps = 1;               // relaxation
  double relax_tolerance = 1e-6;    // relaxation
  long relax_max_iterations = 200000;
  // Refuse decks whose estimated model memory exceeds this (default: the available memory).
  std::optional<double> memory_limit_gb;
  bool dual_horizon = false;  // static solver: bonds act on both ends (dual-horizon form)
  PartitionMethod partition = PartitionMethod::Rcb;  // distributed runs: Zoltan's method
  double rebalance_threshold = 0.10;  // distributed runs: repartition past this imbalance
  bool owned_integration = true;      // distributed explicit runs: each rank advances its region
  std::optional<double> time_step;
  DeckPlace time_step_at{"solver.time_step"};
  double safety = 0.8;
  bool allow_unstable_time_step = false;
  // Multi-rate stepping: nodes whose own stable step allows k dt (k <= multirate_ratio) take it
  // (VelocityVerlet).
  bool multirate = false;
  int multirate_ratio = 2;  // the longest node step, in units of dt
  double end_time = 0.0;
  std::optional<long> steps;
  AdaptSpec adapt;
  OutputSpec output;
};

// Reads and validates a deck. Throws DeckError (file, key, line, what is allowed).
// `overrides`: "key.path=value" pairs (command line --set) applied to the YAML before
// validation, so they are checked like the deck's own keys; a path component that is a number
// indexes a list (loads.0.value=[0, 1e6]); the value is YAML (a number, text, list or mapping).
Deck load_deck(const std::string& path, const std::vector<std::string>& overrides = {});
// Same, from text (tests); `name` stands for the file in messages.
Deck parse_deck(const std::string& text, const std::string& name,
                const std::vector<std::string>& overrides = {});

}  // namespace periadapt
