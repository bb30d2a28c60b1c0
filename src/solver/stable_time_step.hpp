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

// The smallest of dt_i x scale[i]: with scale[i] the ratio of the finest horizon node i's row can
// be refined to over its horizon now, the bound a refined grid will have (the stable step scales
// with the horizon). Every node counts, not only the one that limits dt now: that one may sit at a
// free surface of a finer level, where a level-0 interior node halved is the tighter bound.
StableStep scaled_stable_time_step(const Model& model, const std::vector<double>& scale);

// The bound over the listed nodes only: after a refinement event the rows it rebuilt are the only
// ones whose bound changed, so checking them keeps a stable step stable at the event's cost.
StableStep stable_time_step(const Model& model, const std::vector<std::uint32_t>& nodes);

}  // namespace periadapt
