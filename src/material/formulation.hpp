#pragma once
// The force model of a run: PMB or LPS, each in the source- or dual-horizon pairing, or a
// registered history law (material/bond_laws.cpp). One value replaces flags spread over the
// layers: the deck asks it what a model can do, the solvers and the adaptor ask how its forces
// behave, and material/force_model.cpp dispatches on it to the kernels.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "material/bond_law.hpp"

namespace periadapt {

struct Formulation {
  enum class Kind { Pmb, Lps, HistoryLaw };
  Kind kind = Kind::Pmb;
  bool dual_horizon = false;     // bonds act on both ends with each owner's constants
  const BondLaw* law = nullptr;  // HistoryLaw only

  // From the deck's model.formulation and solver.bond_pairing; nullopt for an unknown name.
  static std::optional<Formulation> named(std::string_view name, bool dual_horizon = false);
  // Every model.formulation value: pmb, lps and the registered history laws.
  static std::vector<std::string> names();

  std::string name() const;   // model.formulation
  std::string label() const;  // banners: PMB, LPS or the law's name

  bool state_based() const { return kind == Kind::Lps; }
  bool keeps_bond_history() const { return kind == Kind::HistoryLaw; }
  // Capabilities.
  // A node's force depends on its own bond row only: multi-rate stepping.
  bool row_local() const { return kind != Kind::Lps && !dual_horizon; }
  // Each row's pass sees the row's own bonds (not the dual pairing's memberships): the force
  // pass records the stretch trigger's measure per row.
  bool passes_row_stretch() const { return !dual_horizon; }
  // Some rows' forces can be recomputed alone (an event's refresh): row-local forces, and LPS
  // from its rows' and their neighbours' dilatations. The dual pairing gathers memberships from
  // other rows: full passes only.
  bool refreshes_rows() const { return !dual_horizon; }
  // The bond-based stiffness (static solve) and the bond-based Poisson ratio apply.
  bool bond_based() const { return kind != Kind::Lps; }
  // Can be re-checked by the refinement overlay; takes a thermal strain.
  bool takes_overlay() const { return kind != Kind::HistoryLaw && !dual_horizon; }
  bool takes_thermal_strain() const { return kind == Kind::Pmb && !dual_horizon; }
  bool works_in_1d() const { return kind != Kind::Lps; }
  // Dual-horizon pairing in a distributed pass: the breaks, found before the forces, become
  // every rank's inside the pass (DualRows::gather_breaks), since the dilatations read every bond.
  bool gathers_breaks_in_pass() const { return kind == Kind::Lps; }
  // Bytes per bond beyond BondFamilies::bytes_per_bond() (transpose, history).
  std::size_t extra_bytes_per_bond() const {
    return (dual_horizon ? 20 : 0) + (keeps_bond_history() ? 8 : 0);
  }
};

}  // namespace periadapt
