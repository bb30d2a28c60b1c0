#pragma once
// The model's internal force density, energy density and stiffness sum, whichever constitutive
// model the deck chose (bond-based PMB or state-based LPS). Solvers call these, never a kernel.
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

// Forces into nodes.f; breaks bonds when allowed; returns the number broken.
std::size_t internal_forces(Model& m, bool allow_breaking,
                            std::vector<std::uint64_t>* broken_log = nullptr,
                            std::vector<double>* W = nullptr);

void energy_density(const Model& m, std::vector<double>& W);

}  // namespace periadapt
