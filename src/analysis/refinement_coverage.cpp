#include "analysis/refinement_coverage.hpp"

#include <cstdint>
#include <vector>

#include "core/cell_grid.hpp"

namespace periadapt {

RefinementCoverage refinement_coverage(const NodeSet& ns, double damage_threshold, double radius) {
  RefinementCoverage c;
  std::vector<std::uint32_t> cracked;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    if (ns.level[i] > 0) ++c.refined;
    if (ns.damage(i) > damage_threshold) {
      cracked.push_back(static_cast<std::uint32_t>(i));
      if (ns.level[i] == 0) ++c.cracked_coarse;
    }
  }
  c.cracked = cracked.size();
  if (cracked.empty()) {
    c.refined_far_from_cracks = c.refined;
    return c;
  }
  const CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, cracked, radius);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || ns.level[i] == 0) continue;
    bool near = false;
    grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, radius,
                         [&](std::uint32_t, double) { near = true; });
    if (!near) ++c.refined_far_from_cracks;
  }
  return c;
}

}  // namespace periadapt
