#pragma once
// Global energies of the model.
#include <vector>

#include "model/model.hpp"

namespace periadapt {

// The sums below are exact (core/exact_sum.hpp): the same bits for any number of threads. With
// an active partition `p` each rank adds its own nodes and the ranks add their sums (collective):
// the serial run's bits again, from the nodes each rank keeps current between syncs.

// Sum of m |v|^2 / 2 over the active nodes.
double kinetic_energy(const NodeSet& nodes, const RowPartition* p = nullptr);
// Total strain energy sum_i W_i V_i; fills W with the energy densities (thesis Eq. 2.14).
double strain_energy(const Model& model, std::vector<double>& W);
// The same sum over given densities W (under `p`, valid for this rank's own rows at least).
double strain_energy_of(const NodeSet& nodes, const std::vector<double>& W,
                        const RowPartition* p = nullptr);
// Total linear momentum (for conservation checks).
std::array<double, 3> linear_momentum(const NodeSet& nodes);

struct MomentumAndKinetic {
  std::array<double, 3> momentum{0, 0, 0};
  double kinetic = 0;
  double momentum_scale = 0;  // sum of m |v|: the yardstick for momentum changes (|p| may be 0)
};
// Both in one pass of exact sums over the active nodes (collective under an active partition
// `p`, as above). linear_momentum is its first half.
MomentumAndKinetic momentum_and_kinetic(const NodeSet& nodes, const RowPartition* p = nullptr);

}  // namespace periadapt
