#include "adapt/event_relaxation.hpp"

#include <algorithm>

#include "solver/internal_forces.hpp"

namespace periadapt {

std::vector<std::uint32_t> relax_event_rows(Model& m, const std::vector<std::uint32_t>& rebuilt,
                                            std::size_t first_new, int sweeps) {
  NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  const std::size_t n = ns.size();
  if (sweeps <= 0 || first_new >= n) return {};
  // Which rows: those bonded to a new node, a test on the bonds rather than on the rebuild
  // radius, so that a mirror-symmetric grid gets a mirror-symmetric set (a radius decides nodes
  // at its edge by round-off). Only rebuilt rows can hold a bond to a new node.
  std::vector<char> held(n, 0);
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes) held[i] = 1;
  std::vector<std::uint32_t> rows;
  for (std::uint32_t i : rebuilt) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kBoundary) || held[i]) continue;
    bool near_new = i >= first_new;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i) && !near_new; ++k)
      near_new = bf.neighbor[k] >= first_new;
    if (near_new) rows.push_back(i);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  if (rows.empty()) return {};
  // The diagonal of a bond-based stiffness is at most the stiffness sum (a bond along one axis
  // puts all of its spring there), and twice the sum bounds the whole stiffness (Gershgorin):
  // dividing by the sum, the sweeps cannot overshoot. LPS's dilatation terms are bounded by the
  // same sum of the equal P-wave modulus in practice, as the stable time step assumes.
  const MaterialContext ctx = material_context(m);
  std::vector<double> K(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) K[r] = material_stiffness_row(ns, bf, ctx, rows[r]);
  // LPS too: a rows-only pass recomputes the dilatations the rows' forces read.
  const bool rows_only = m.formulation.refreshes_rows();
  for (int s = 0; s < sweeps; ++s) {
    if (rows_only)
      internal_forces_rows(m, false, rows);
    else
      internal_forces(m, false);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const std::uint32_t i = rows[r];
      if (!(K[r] > 0)) continue;
      for (int d = 0; d < ns.dim; ++d) ns.u[d][i] += (ns.f[d][i] - ns.density[i] * ns.a[d][i]) / K[r];
    }
    for (std::uint32_t i : rows) ns.sync_current(i);
  }
  std::vector<char> touched(n, 0);
  for (std::uint32_t i : rows) {
    touched[i] = 1;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) touched[bf.neighbor[k]] = 1;
  }
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < n; ++i)
    if (touched[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

}  // namespace periadapt
