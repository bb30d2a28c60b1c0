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

// Whether a node's force depends on its own bond row only (plain bond-based PMB): then the forces
// of a set of rows can be computed alone (internal_forces_rows).
bool forces_are_row_local(const Model& m);
// The forces of the nodes `rows` only (forces_are_row_local(m) must hold); the others keep theirs.
// With W, the rows' energy densities are updated too (W must hold the others').
std::size_t internal_forces_rows(Model& m, bool allow_breaking, const std::vector<std::uint32_t>& rows,
                                 std::vector<std::uint64_t>* broken_log = nullptr,
                                 std::vector<double>* W = nullptr);

void energy_density(const Model& m, std::vector<double>& W);
// Stress of every node, the derivative of its energy density above with respect to a homogeneous
// strain (row-major 3 x 3 per node; LPS also leaves the dilatation in m.lps_scratch.theta).
void stress_density(const Model& m, std::vector<double>& sigma);

}  // namespace periadapt
