#pragma once
// Bond-based laws with a history per bond, beside the PMB and LPS kernels. A law is one file
// (its bond response, its deck key and how its breaking stretch follows the horizon) and one
// line in material/bond_laws.cpp; the solvers, the adaptor and the deck reach it through the
// BondLaw entry below. The elastic branch is PMB's (micromodulus, Poisson ratio, stable step,
// static stiffness), so everything calibrated for PMB holds until a bond leaves it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/dual_rows.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

// What a law's kernels need besides the nodes and bonds.
struct BondLawCall {
  InfluenceShape shape = InfluenceShape::Constant;
  double onset_stretch = 0;  // where the law leaves its elastic branch (from its deck key)
  bool allow_breaking = true;
  std::vector<std::uint64_t>* broken_log = nullptr;  // bonds broken by this call
  std::vector<double>* W = nullptr;                  // energy densities from the same pass
  const std::vector<std::uint32_t>* rows = nullptr;  // only these rows (others keep theirs)
  std::vector<double>* breakable_stretch = nullptr;  // stretch trigger's measure per row
  const DualRows* split = nullptr;                   // dual form: a distributed pass's share
};

struct BondLaw {
  std::string_view name;         // model.formulation
  std::string_view description;  // one line for messages and the docs
  // Its one material key: a stress (Pa) that sets onset_stretch = stress / M, M the stress of
  // an equal all-round stretch of the bond-based material (3D: 3K; 1D: E).
  std::string_view stress_key;
  std::string_view stress_meaning;
  bool needs_fracture_energy = false;  // material.fracture_energy required
  // The stretch at which a bond breaks, from the brittle PMB critical stretch of the node's
  // horizon (the G0 calibration) and the onset stretch: the law dissipates G0 over a crack.
  double (*breaking_stretch)(double brittle_s0, double onset_stretch) = nullptr;
  // Forces (and, when asked, energy densities and the trigger's stretch) of the rows; updates
  // each bond's history (bonds.state) and breaks bonds past their breaking stretch.
  std::size_t (*forces)(NodeSet&, BondFamilies&, const BondLawCall&) = nullptr;
  // The same in the dual-horizon form (bonds.t_* built; call.rows must be null; call.split
  // for a distributed pass).
  std::size_t (*dual_forces)(NodeSet&, BondFamilies&, const BondLawCall&) = nullptr;
  // Stored (recoverable) energy density of every node (call.rows: of those rows, the others
  // keep theirs) from the current state.
  void (*energy_density)(const NodeSet&, const BondFamilies&, const BondLawCall&,
                         std::vector<double>&) = nullptr;
  // sigma_i = 1/2 sum_j c g F beta V e (x) xi, F the law's force factor (row-major 3 x 3).
  void (*stress)(const NodeSet&, const BondFamilies&, const BondLawCall&,
                 std::vector<double>&) = nullptr;
  // A new bond (children's bonds, rows searched again without a survivor) starts at history 0.
};

// Every registered law (material/bond_laws.cpp), and one by name (nullptr if none).
const std::vector<const BondLaw*>& bond_laws();
const BondLaw* find_bond_law(std::string_view name);

// Stress of an equal all-round stretch per unit stretch, of the bond-based material with
// Young's modulus E: 1D E; 3D (nu = 1/4) 3K = 2E; plane stress (nu = 1/3) E/(1-nu) = 3E/2;
// plane strain (nu = 1/4) E/((1+nu)(1-2nu)) = 8E/5.
double all_round_modulus(int dim, PlaneCondition plane, double E);

}  // namespace periadapt
