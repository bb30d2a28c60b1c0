#pragma once
// The point fields every VTU snapshot carries: displacement, velocity, damage, strain-energy
// density, horizon, refinement level, volume, the stretch ratio (largest stretch of the node's
// intact breakable bonds over its critical stretch, analysis/breakable_stretch.hpp); with `stress` also the stress (the derivative of
// the node's energy density, solver/internal_forces.hpp), the small strain fitted over the
// visible family (linear least squares, so exact for a linear displacement field and never
// across a crack) and, for LPS, the dilatation. Tensors are row-major 3 x 3.
#include <vector>

#include "io/vtu_writer.hpp"
#include "model/model.hpp"

namespace periadapt {

// W: strain-energy density per node (same length as the node set).
std::vector<PointField> snapshot_fields(const Model& m, const std::vector<double>& W,
                                        bool stress = false);

}  // namespace periadapt
