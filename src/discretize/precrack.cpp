#include "discretize/precrack.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

std::size_t apply_precracks(const NodeSet& nodes, BondFamilies& bonds,
                            const std::vector<PreCrack>& cracks, const std::vector<char>* rows,
                            std::vector<std::size_t>* per_crack) {
  std::size_t total = 0;
  const std::size_t n = nodes.size();
  if (per_crack) per_crack->assign(cracks.size(), 0);
  for (std::size_t ci = 0; ci < cracks.size(); ++ci) {
    const PreCrack& c = cracks[ci];
    std::size_t cut = 0;
    // Only nodes within one horizon of the crack's bounding box can own a crossing bond.
    Box bb;
    const int np = c.planar3d ? 4 : 2;
    for (int d = 0; d < 3; ++d) {
      bb.lo[d] = bb.hi[d] = c.points[0][d];
      for (int k = 1; k < np; ++k) {
        bb.lo[d] = std::min(bb.lo[d], c.points[k][d]);
        bb.hi[d] = std::max(bb.hi[d], c.points[k][d]);
      }
    }
#pragma omp parallel for schedule(static) reduction(+ : cut)
    for (std::size_t i = 0; i < n; ++i) {
      if (rows && !(i < rows->size() && (*rows)[i])) continue;
      const Vec3 p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
      const double h = nodes.horizon[i];
      bool near = true;
      for (int d = 0; d < nodes.dim; ++d)
        if (p[d] < bb.lo[d] - h || p[d] > bb.hi[d] + h) near = false;
      if (!near) continue;
      for (std::uint64_t k = bonds.begin(i); k < bonds.end(i); ++k) {
        if (!BondFamilies::intact(bonds.beta[k])) continue;
        const std::uint32_t j = bonds.neighbor[k];
        const Vec3 q{nodes.x[0][j], nodes.x[1][j], nodes.x[2][j]};
        const bool crosses = c.planar3d ? bond_crosses_quad(p, q, c.points)
                                        : bond_crosses_segment(p, q, c.points[0], c.points[1]);
        if (crosses) {
          bonds.beta[k] = -bonds.beta[k];
          ++cut;
        }
      }
    }
    if (per_crack) (*per_crack)[ci] = cut;
    total += cut;
  }
  return total;
}

}  // namespace periadapt
