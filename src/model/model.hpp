#pragma once
// The simulation model the solvers act on: nodes, bond families, material law, loads and
// prescribed motions. Built from a deck by build_model(); mutated between steps by adaptivity.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/bond_families.hpp"
#include "core/expression.hpp"
#include "core/geometry.hpp"
#include "core/node_set.hpp"
#include "discretize/families.hpp"
#include "discretize/precrack.hpp"
#include "discretize/surface_correction.hpp"
#include "material/formulation.hpp"
#include "material/lps.hpp"
#include "material/contact.hpp"
#include "material/impactor.hpp"
#include "material/micromodulus.hpp"
#include "overlay/pdro.hpp"
#include "model/time_function.hpp"

namespace periadapt {

struct BodyLoad {
  std::string name;
  std::vector<std::uint32_t> nodes;
  std::array<double, 3> density{0, 0, 0};  // body-force density at amplitude 1 (N/m^3)
  TimeFunction amplitude;
};

struct PrescribedMotion {
  enum class Kind { Velocity, Displacement } kind = Kind::Velocity;
  std::string name;
  std::vector<std::uint32_t> nodes;
  std::array<std::optional<Expression>, 3> component;  // unset: free component
  Shape region;  // where it applies (children created inside it inherit it)
};

struct MaterialLaw {
  std::string name = "material";
  double E = 0, nu = 0, rho = 0;
  double G0 = 0;                 // 0 when s0 was given directly
  double s0 = 0;
  double c0 = 0;
  double wave_speed = 0;         // P-wave speed for reports
  double thermal_strain = 0;     // alpha dT (PMB): bond stretch s - alpha dT
  InfluenceShape shape = InfluenceShape::Constant;
  PlaneCondition plane = PlaneCondition::None;
  double thickness = 1.0;
  LpsConstants lps_constants;  // the LPS formulation's moduli
  double onset_stretch = INFINITY;  // where a history law leaves its elastic branch
  // Young's modulus of the bond-based material with the same P-wave modulus: its micromodulus
  // (stored per node) drives the stable time step and the relaxation masses for both models.
  double bb_equivalent_E = 0;
  // Micromoduli divided by the quadrature's bulk lattice moment at each level's m
  // (discretization.micromodulus_calibration: lattice), so that every level has the bond
  // stiffness of the continuum and levels of different m meet without an impedance jump.
  bool lattice_calibration = false;
};

struct Model {
  NodeSet nodes;
  BondFamilies bonds;
  Formulation formulation;  // which force model, and what it can do
  MaterialLaw material;
  bool damage_enabled = true;
  std::vector<BodyLoad> loads;
  std::vector<PrescribedMotion> motions;
  std::size_t precrack_bonds = 0;  // directed entries broken by pre-cracks
  double grid_spacing = 0;
  double horizon = 0;
  double family_build_seconds = 0;  // wall time of the neighbor search and CSR build
  // What rebuilding families after refinement needs again.
  QuadratureSpec quadrature;
  std::vector<PreCrack> cracks;
  double lattice_rotation = 0.0;  // radians (2D grids): orientation of children offsets
  Box body;                       // the body box; refinement creates no node outside it
  std::vector<Shape> holes;       // ... nor inside a hole
  std::optional<Shape> body_clip; // ... nor outside a non-box body (disk)
  SurfaceCorrection surface_correction = SurfaceCorrection::None;
  PdroSpec pdro;              // refinement overlay for bond failure (PMB)
  ContactSpec contact;        // short-range repulsion between nodes (material/contact.hpp)
  std::vector<Impactor> impactors;  // rigid bodies that strike it (material/impactor.hpp)
  mutable LpsScratch lps_scratch;  // per-node weighted volume and dilatation (LPS)
  // With track_breakable_stretch (the stretch trigger, row-local forces): each row's largest
  // stretch of its intact breakable bonds, from its latest force pass.
  bool track_breakable_stretch = false;
  std::vector<double> breakable_stretch;
};

// Bytes per node for memory reports: the node arrays, the bond-row index and, with loads, the
// solver's body-force densities.
inline std::size_t model_bytes_per_node(const Model& m) {
  return NodeSet::bytes_per_node() + m.bonds.row_index_bytes_per_node() +
         (m.loads.empty() ? 0 : 3 * sizeof(double));
}

}  // namespace periadapt
