#pragma once
// Force resultants that users plot: per load its applied force, per boundary condition the
// reaction of its supports, each with the volume-weighted mean displacement of its nodes. The
// explicit, static and relaxation runs write them in the same columns (history.csv) and draw the
// same load-displacement picture.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/geometry.hpp"
#include "input/deck.hpp"
#include "model/model.hpp"

namespace periadapt {


// "load_NAME_fx_N,load_NAME_ux_m,...,bc_NAME_fx_N,..." with a trailing comma.
std::string resultant_header(const Model& m);

// The values under resultant_header, with a trailing comma. Under an active partition `p` the
// mean displacements are collective (analysis/energy.hpp), and so must `reaction` be where it is.
std::string resultant_columns(const Model& m,
                              const std::function<Vec3(const BodyLoad&)>& applied,
                              const std::function<Vec3(const PrescribedMotion&)>& reaction,
                              const RowPartition* p = nullptr);

// {"loads": {NAME: {force_N, mean_displacement_m}}, "boundary_conditions": {...}}.
nlohmann::json resultants_json(const Model& m,
                               const std::function<Vec3(const BodyLoad&)>& applied,
                               const std::function<Vec3(const PrescribedMotion&)>& reaction);

// Volume-weighted over the active ones of `nodes`, summed exactly (collective under an active
// partition `p`: each rank adds its own nodes).
Vec3 mean_displacement(const NodeSet& ns, const std::vector<std::uint32_t>& nodes,
                       const RowPartition* p = nullptr);

// A load's force at the given amplitude: amplitude x density x volume of its active nodes.
Vec3 load_force(const NodeSet& ns, const BodyLoad& load, double amplitude);

// In equilibrium the supports balance what the other forces leave at their nodes: the reaction
// is minus the sum over the region's active nodes and constrained components of
// (internal + body force density) x volume. `internal`: force densities per component.
Vec3 equilibrium_reaction(const Model& m, const PrescribedMotion& pm,
                            const std::array<std::vector<double>, 3>& internal,
                            double load_amplitude_factor);

// output.load_displacement: the chosen pair of history columns drawn against each other into
// DIR/load_displacement.png (nothing when the history lacks them). `from_origin`: the curve
// starts at (0, 0), the unloaded state the history has no row of (relaxation runs).
void write_load_displacement_png(const std::string& dir, const std::string& history,
                                 const LoadDisplacementPlot& plot, const Model& m,
                                 bool from_origin = false);

}  // namespace periadapt
