#include "material/lps_dual.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

namespace {

double bond_extension(const NodeSet& ns, std::size_t a, std::size_t b, double x, double d[3]) {
  double r2 = 0;
  for (int e = 0; e < ns.dim; ++e) {
    d[e] = ns.cur[4 * b + static_cast<std::size_t>(e)] - ns.cur[4 * a + static_cast<std::size_t>(e)];
    r2 += d[e] * d[e];
  }
  return std::sqrt(r2) - x;
}

}  // namespace

std::size_t lps_dual_forces(NodeSet& ns, BondFamilies& bf, InfluenceShape shape,
                            const LpsConstants& c, bool allow_breaking, LpsScratch& sc,
                            std::vector<std::uint64_t>* log, std::vector<double>* Wout,
                            const DualRows& split) {
  const std::size_t n = ns.size();
  const std::size_t n_rows = split.count(n, true);
  // 1. Breaking, each owner on its own memberships.
  // (bond, owner): after a refinement event rows are no longer stored in node order, so the
  // owner is recorded, not inferred from the bond's index.
  BrokenMemberships newly;
  if (allow_breaking) {
#pragma omp parallel
    {
      BrokenMemberships mine;
#pragma omp for schedule(dynamic, 512)
      for (std::size_t r = 0; r < n_rows; ++r) {
        const std::size_t i = split.at(r, true);
        if (!(ns.flags[i] & kActive) || (ns.flags[i] & kNoFail)) continue;
        const double s0 = ns.critical_stretch[i];
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
          if (!BondFamilies::intact(bf.beta[k]) || bf.inv_length[k] < 0.0) continue;
          double d[3];
          const double x = bf.length(k);
          if (bond_extension(ns, i, bf.neighbor[k], x, d) > s0 * x)
            mine.emplace_back(k, static_cast<std::uint32_t>(i));
        }
      }
#pragma omp critical(lps_dual_broken)
      newly.insert(newly.end(), mine.begin(), mine.end());
    }
    std::sort(newly.begin(), newly.end());
    if (split.gather_breaks) split.gather_breaks(newly);
    for (const auto& [k, o] : newly) {
      if (k == kBondNotHeld) continue;  // its row's owner shares the row's weight after the pass
      ns.broken_weight[o] += static_cast<double>(bf.beta[k]) * ns.volume[bf.neighbor[k]];
      bf.beta[k] = -bf.beta[k];
      if (log) log->push_back(k);
    }
  }
  // 2. Weighted volumes and dilatations (the plain kernel's first pass).
  // A distributed pass needs the states of its rows and of the owners of their dual memberships.
  if (Wout) lps_energy_density(ns, bf, shape, c, sc, *Wout, false, split.first);
  else lps_dilatation(ns, bf, shape, c, sc, false, split.first);
  // 3. Forces: own memberships with i's state, dual memberships with the owner's state.
  const double Dk = c.D * c.kappa, am = c.alpha * c.mu, invD = 1.0 / c.D;
  auto t_state = [&](std::size_t owner, double x, double e) {
    const double m = sc.m[owner], th = sc.theta[owner];
    if (!(m > 0)) return 0.0;
    const double w = influence(shape, std::min(1.0, x / ns.horizon[owner]));
    return (Dk * th * w * x + am * w * (e - th * x * invD)) / m;
  };
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t r = 0; r < n_rows; ++r) {
    const std::size_t i = split.at(r, true);
    if (!(ns.flags[i] & kActive)) continue;
    double a[3] = {0, 0, 0};
    // Membership k of `owner`'s family between i and `other`: the owner's force state times the
    // other end's volume, along i -> other (for i's own bonds owner = i; for its dual horizon,
    // the reaction of o's membership, owner = other = o).
    auto add = [&](std::size_t owner, std::size_t other, std::uint64_t k) {
      if (!BondFamilies::intact(bf.beta[k])) return;
      const double x = bf.length(k);
      double d[3];
      const double e = bond_extension(ns, i, other, x, d);
      const double fr = t_state(owner, x, e) * static_cast<double>(bf.beta[k]) * ns.volume[other] / (x + e);
      for (int p = 0; p < ns.dim; ++p) a[p] += fr * d[p];
    };
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) add(i, bf.neighbor[k], k);
    for (std::uint64_t q = bf.t_offsets[i]; q < bf.t_offsets[i + 1]; ++q)
      add(bf.t_owner[q], bf.t_owner[q], bf.t_bond[q]);
    for (int p = 0; p < ns.dim; ++p) ns.f[p][i] = a[p];
  }
  return newly.size();
}

}  // namespace periadapt
