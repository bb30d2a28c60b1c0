#pragma once
// Stable explicit time step for bond-based models (Silling & Askari 2005): per node
// dt_i = sqrt(2 rho_i / sum_j C_ij V_j) with C_ij = c g / |xi|; the bound is the minimum.
#include <cstddef>

#include "model/model.hpp"

namespace periadapt {

struct StableStep {
  double dt = 0;
  std::size_t node = 0;  // node that limits the step
};

StableStep stable_time_step(const Model& model);

}  // namespace periadapt
