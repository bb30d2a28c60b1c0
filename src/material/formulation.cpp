#include "material/formulation.hpp"

namespace periadapt {

std::optional<Formulation> Formulation::named(std::string_view name, bool dual_horizon) {
  Formulation f;
  f.dual_horizon = dual_horizon;
  if (name == "pmb") return f;
  if (name == "lps") {
    f.kind = Kind::Lps;
    return f;
  }
  if (const BondLaw* law = find_bond_law(name)) {
    f.kind = Kind::HistoryLaw;
    f.law = law;
    return f;
  }
  return std::nullopt;
}

std::vector<std::string> Formulation::names() {
  std::vector<std::string> out{"pmb", "lps"};
  for (const BondLaw* law : bond_laws()) out.emplace_back(law->name);
  return out;
}

std::string Formulation::name() const {
  return kind == Kind::Pmb ? "pmb" : kind == Kind::Lps ? "lps" : std::string(law->name);
}

std::string Formulation::label() const {
  return kind == Kind::Pmb ? "PMB" : kind == Kind::Lps ? "LPS" : std::string(law->name);
}

}  // namespace periadapt
