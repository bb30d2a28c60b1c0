#pragma once
// Structure-of-arrays node storage. Nodes are only ever appended (refinement adds children and
// deactivates parents), so ids stay stable for the whole run.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace periadapt {

enum NodeFlag : std::uint8_t {
  kActive = 1u << 0,
  kNoFail = 1u << 1,   // bonds touching this node never break
  kBoundary = 1u << 2, // has a prescribed displacement or velocity component
};

struct NodeSet {
  int dim = 2;
  std::array<std::vector<double>, 3> x;  // reference position
  std::array<std::vector<double>, 3> u;  // displacement
  std::array<std::vector<double>, 3> v;  // velocity
  std::array<std::vector<double>, 3> a;  // acceleration
  std::array<std::vector<double>, 3> f;  // internal force density (N/m^3)
  // (external body-force densities live with the solvers, only when a model has loads)
  // Current position y = x + u and volume packed per node [y0, y1, y2, V]: the bond loops
  // gather one cache line per neighbor instead of four.
  std::vector<double> cur;
  std::vector<double> volume;    // quadrature volume (m^3)
  std::vector<double> spacing;   // grid spacing of the node's cell
  std::vector<double> horizon;   // per-node horizon delta_i
  std::vector<double> micromodulus;       // c0 of the source node (shape peak value)
  std::vector<double> critical_stretch;   // s0 of the source node
  std::vector<double> density;
  std::vector<double> broken_weight;      // volume-weighted broken bonds (damage numerator)
  std::vector<double> family_weight;      // volume-weighted family size (damage denominator)
  std::vector<std::int8_t> level;
  std::vector<std::int32_t> parent;  // refinement parent (-1 for nodes of the initial grid)
  std::vector<std::uint8_t> flags;
  // Material block of each node (several materials, Model::block_materials); empty for one.
  std::vector<std::uint8_t> block;

  std::size_t size() const { return volume.size(); }

  // Appends a node with zero kinematic state; returns its id.
  std::size_t append(const std::array<double, 3>& pos, double vol, double dx) {
    for (int d = 0; d < 3; ++d) {
      x[d].push_back(pos[d]);
      u[d].push_back(0.0);
      v[d].push_back(0.0);
      a[d].push_back(0.0);
      f[d].push_back(0.0);
    }
    cur.insert(cur.end(), {pos[0], pos[1], pos[2], vol});
    volume.push_back(vol);
    spacing.push_back(dx);
    horizon.push_back(0.0);
    micromodulus.push_back(0.0);
    critical_stretch.push_back(0.0);
    density.push_back(0.0);
    broken_weight.push_back(0.0);
    family_weight.push_back(0.0);
    level.push_back(0);
    parent.push_back(-1);
    flags.push_back(kActive);
    if (!block.empty()) block.push_back(0);
    return volume.size() - 1;
  }

  double current(std::size_t i, int d) const { return cur[4 * i + d]; }
  // Refreshes the packed current position and volume of node i from x, u and volume.
  void sync_current(std::size_t i) {
    for (int d = 0; d < 3; ++d) cur[4 * i + d] = x[d][i] + u[d][i];
    cur[4 * i + 3] = volume[i];
  }
  void sync_all_current() {
    for (std::size_t i = 0; i < size(); ++i) sync_current(i);
  }

  double damage(std::size_t i) const {
    return family_weight[i] > 0 ? broken_weight[i] / family_weight[i] : 0.0;
  }

  // Bytes held per node by the arrays above (for memory reports).
  static constexpr std::size_t bytes_per_node() { return 5 * 3 * 8 + 4 * 8 + 9 * 8 + 2 + 4; }
};

// Reference and current bond vectors from node i to node j (the first ns.dim components; the
// others 0) and the current length |y|.
inline double bond_vectors(const NodeSet& ns, std::size_t i, std::size_t j, double xi[3],
                           double y[3]) {
  double r2 = 0;
  for (int d = 0; d < 3; ++d) {
    xi[d] = d < ns.dim ? ns.x[d][j] - ns.x[d][i] : 0.0;
    y[d] = d < ns.dim ? ns.cur[4 * j + d] - ns.cur[4 * i + d] : 0.0;
    r2 += y[d] * y[d];
  }
  return std::sqrt(r2);
}

}  // namespace periadapt
