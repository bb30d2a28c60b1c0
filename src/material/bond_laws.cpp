// The registry of history laws: adding a law is its file and one entry in this list.
#include "material/bond_law.hpp"

#define PERIADAPT_BOND_LAWS(X) \
  X(kElasticPerfectlyPlastic)  \
  X(kBilinearSoftening)

namespace periadapt {

#define PERIADAPT_DECLARE(law) extern const BondLaw law;
PERIADAPT_BOND_LAWS(PERIADAPT_DECLARE)
#undef PERIADAPT_DECLARE

const std::vector<const BondLaw*>& bond_laws() {
#define PERIADAPT_ENTRY(law) &law,
  static const std::vector<const BondLaw*> laws{PERIADAPT_BOND_LAWS(PERIADAPT_ENTRY)};
#undef PERIADAPT_ENTRY
  return laws;
}

const BondLaw* find_bond_law(std::string_view name) {
  for (const BondLaw* l : bond_laws())
    if (l->name == name) return l;
  return nullptr;
}

double all_round_modulus(int dim, PlaneCondition plane, double E) {
  if (dim == 1) return E;
  if (dim == 3) return 2.0 * E;  // 3K, nu = 1/4
  return plane == PlaneCondition::Strain ? 1.6 * E : 1.5 * E;
}

}  // namespace periadapt
