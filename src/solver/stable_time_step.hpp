#pragma once
// Stable explicit time step for bond-based models (Silling & Askari 2005): per node
// dt_i = sqrt(2 rho_i / sum_j C_ij V_j) with C_ij = c g / |xi|; the bound is the minimum.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

struct StableStep {
  double dt = 0;
  std::size_t node = 0;  // node that limits the step
};

StableStep stable_time_step(const Model& model);

// The bound over the listed nodes only: after a refinement event the rows it rebuilt are the only
// ones whose bound changed, so checking them keeps a stable step stable at the event's cost.
StableStep stable_time_step(const Model& model, const std::vector<std::uint32_t>& nodes);

}  // namespace periadapt
