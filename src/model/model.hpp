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
#include "material/force_model.hpp"
#include "material/formulation.hpp"
#include "material/lps.hpp"
#include "material/contact.hpp"
#include "material/impactor.hpp"
#include "material/material_law.hpp"
#include "material/blocks.hpp"
#include "material/micromodulus.hpp"
#include "overlay/pdro.hpp"
#include "parallel/row_partition.hpp"
#include "model/ghost_table.hpp"
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


struct Model {
  NodeSet nodes;
  BondFamilies bonds;
  Formulation formulation;  // which force model, and what it can do
  MaterialLaw material;
  // Several materials (deck list blocks): one law per block, [0] = `material`, and the rules of
  // bonds between blocks (material/blocks.hpp); empty for one material. Node i's block is
  // nodes.block[i].
  std::vector<MaterialLaw> block_materials;
  BlockPairs block_pairs;
  // Distributed runs: which rows this rank computes (parallel/row_partition.hpp).
  RowPartition partition;
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
  // Refinement events correct only their window and the ring around it (set by the adaptor for
  // the run's events); refinement during set-up searches and corrects the whole model, which
  // costs once and leaves the canonical factors.
  bool window_surface_correction = false;
  bool interface_fit = false;  // adapt.interface_fit: rebuilt interface rows pass the patch test
  GhostTable ghost;            // ghost-force correction of interface rows (solver/ghost_correction.hpp)
  PdroSpec pdro;              // refinement overlay for bond failure (PMB)
  ContactSpec contact;        // short-range repulsion between nodes (material/contact.hpp)
  std::vector<Impactor> impactors;  // rigid bodies that strike it (material/impactor.hpp)
  mutable LpsScratch lps_scratch;  // per-node weighted volume and dilatation (LPS)
  // With track_breakable_stretch (the stretch trigger, row-local forces): each row's largest
  // stretch of its intact breakable bonds, from its latest force pass.
  bool track_breakable_stretch = false;
  std::vector<double> breakable_stretch;
};

// What the force model's dispatch (material/force_model.hpp) reads of the model.
inline MaterialContext material_context(const Model& m) {
  return {m.formulation, m.material, m.lps_scratch, &m.pdro, &m.block_pairs};
}

// The law of node i's block.
inline const MaterialLaw& node_material(const Model& m, std::size_t i) {
  return m.nodes.block.empty() ? m.material : m.block_materials[m.nodes.block[i]];
}

// The uniaxial (P-wave) modulus of every block; empty for one material.
inline std::vector<double> block_uniaxial_moduli(const Model& m) {
  std::vector<double> out;
  for (const MaterialLaw& l : m.block_materials)
    out.push_back(p_wave_modulus(m.nodes.dim, l.plane, l.E, l.nu));
  return out;
}

// Bytes per node for memory reports: the node arrays, the bond-row index and, with loads, the
// solver's body-force densities.
inline std::size_t model_bytes_per_node(const Model& m) {
  return NodeSet::bytes_per_node() + m.bonds.row_index_bytes_per_node() +
         (m.nodes.block.empty() ? 0 : sizeof(std::uint8_t)) +
         (m.loads.empty() ? 0 : 3 * sizeof(double));
}

}  // namespace periadapt
