#pragma once
// Global energies of the model.
#include <vector>

#include "model/model.hpp"

namespace periadapt {

double kinetic_energy(const NodeSet& nodes);
// Total strain energy sum_i W_i V_i; fills W with the energy densities (thesis Eq. 2.14).
double strain_energy(const Model& model, std::vector<double>& W);
// Total linear momentum (for conservation checks).
std::array<double, 3> linear_momentum(const NodeSet& nodes);

}  // namespace periadapt
