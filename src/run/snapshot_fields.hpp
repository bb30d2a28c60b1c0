#pragma once
// The point fields every VTU snapshot carries: displacement, velocity, damage, strain-energy
// density, horizon, refinement level, volume.
#include <vector>

#include "io/vtu_writer.hpp"
#include "model/model.hpp"

namespace periadapt {

// W: strain-energy density per node (same length as the node set).
std::vector<PointField> snapshot_fields(const Model& m, const std::vector<double>& W);

}  // namespace periadapt
