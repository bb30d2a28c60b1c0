#pragma once
// The model's internal force density, energy density and stress: the material's, through its
// one dispatch point (material/force_model.hpp), plus contact and rigid impactors; in a
// distributed run, this rank's share and the exchange after it. Solvers call these.
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

// Forces into nodes.f; breaks bonds when allowed; returns the number broken.
std::size_t internal_forces(Model& m, bool allow_breaking,
                            std::vector<std::uint64_t>* broken_log = nullptr,
                            std::vector<double>* W = nullptr);

// The forces of the nodes `rows` only (m.formulation.refreshes_rows() must hold); the others
// keep theirs. State-based forces read the rows' neighbours' dilatations, computed here too.
// With W, the rows' energy densities are updated too (W must hold the others').
std::size_t internal_forces_rows(Model& m, bool allow_breaking, const std::vector<std::uint32_t>& rows,
                                 std::vector<std::uint64_t>* broken_log = nullptr,
                                 std::vector<double>* W = nullptr);

// The rows whose forces read the families of `rows` (ascending): `rows` themselves where a
// node's force depends on its own row only; state-based, also every active node within the
// largest search radius of one of them (its force reads their dilatations).
std::vector<std::uint32_t> rows_reading(const Model& m, const std::vector<std::uint32_t>& rows);

void energy_density(const Model& m, std::vector<double>& W);
// The material's energy density of the listed rows only (the others' left as they are); with held
// bond rows (parallel/held_rows.hpp) each owner evaluates its own and shares them (collective).
// `own_rows_only`: in a distributed run, only this rank's rows, kept here (no collective).
void energy_density_rows(const Model& m, std::vector<double>& W,
                         const std::vector<std::uint32_t>& rows, bool own_rows_only = false);
// Stress of every node, the derivative of its energy density above with respect to a homogeneous
// strain (row-major 3 x 3 per node; LPS also leaves the dilatation in m.lps_scratch.theta).
void stress_density(const Model& m, std::vector<double>& sigma);

}  // namespace periadapt
