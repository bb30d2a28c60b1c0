#pragma once
// The ghost-force table of adapt.ghost_correction (solver/ghost_correction.hpp): per corrected
// row, the force density a unit uniform strain component puts on it, and the inverse moment
// matrix of its bonds for fitting its strain.
#include <cstdint>
#include <vector>

namespace periadapt {

struct GhostTable {
  bool enabled = false;
  bool rebuild_all = true;             // no table yet (set-up, restart)
  std::vector<std::uint32_t> pending;  // rows whose families changed since the last update
  int components = 0;                  // 1 (1D), 3 (2D: xx, yy, xy), 6 (3D: + zz, yz, xz)
  std::vector<std::uint32_t> rows;     // corrected rows
  std::vector<double> G;               // rows x components x 3: force density per unit strain
  std::vector<double> Kinv;            // rows x 9: inverse of sum xi (x) xi over the row's bonds
  std::vector<std::uint32_t> slot;     // per node: index into rows, or UINT32_MAX
  // Per node: whether cells cover its ball, and the horizon that was checked (NaN: not yet).
  // Refinement and coarsening repartition cells without changing their union, so a node's
  // answer holds until its horizon changes.
  std::vector<char> covered;
  std::vector<double> covered_at;
};

}  // namespace periadapt
