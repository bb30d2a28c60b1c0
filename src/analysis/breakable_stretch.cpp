#include "analysis/breakable_stretch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace periadapt {

namespace {

// Largest stretch of row i's intact breakable bonds; with own_level, only the bonds to nodes of
// level <= row i's.
double largest_stretch_of_row(const Model& m, std::uint32_t i, bool own_level) {
  const NodeSet& ns = m.nodes;
  const std::int8_t* lv = ns.level.data();
  const std::int8_t li = own_level ? lv[i] : std::numeric_limits<std::int8_t>::max();
  const BondFamilies& bf = m.bonds;
  const double eth = m.material.thermal_strain;
  const double* yp = ns.cur.data();
  const double yi0 = yp[4 * std::size_t{i}], yi1 = yp[4 * std::size_t{i} + 1],
               yi2 = yp[4 * std::size_t{i} + 2];
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* inv_len = bf.inv_length.data();
  const float* bt = bf.beta.data();
  if (m.block_pairs.active()) {
    const double* isf = m.block_pairs.inv_stretch_row(ns.block[i]);
    double sn = -INFINITY;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      if (!(bt[k] > 0.0f) || !(inv_len[k] > 0.0) || lv[nbr[k]] > li) continue;
      const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
      const double d0 = yp[j] - yi0, d1 = yp[j + 1] - yi1, d2 = yp[j + 2] - yi2;
      const double s = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) * inv_len[k] - 1.0 - eth;
      sn = std::max(sn, s * isf[ns.block[nbr[k]]]);
    }
    return sn;
  }
  // (|y| / |xi|)^2, largest of the row, branch-free so that it vectorizes: broken bonds have
  // beta < 0, unbreakable ones 1/|xi| < 0.
  double q = -1.0;
#pragma omp simd reduction(max : q)
  for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
    const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
    const double d0 = yp[j] - yi0, d1 = yp[j + 1] - yi1, d2 = yp[j + 2] - yi2;
    const double il = inv_len[k];
    const double v = (d0 * d0 + d1 * d1 + d2 * d2) * il * il;
    q = std::max(q, (bt[k] > 0.0f && il > 0.0 && lv[nbr[k]] <= li) ? v : -1.0);
  }
  return q < 0.0 ? -INFINITY : std::sqrt(q) - 1.0 - eth;
}

}  // namespace

double largest_breakable_stretch(const Model& m, std::uint32_t i) {
  return largest_stretch_of_row(m, i, false);
}

double largest_breakable_stretch_own_level(const Model& m, std::uint32_t i) {
  return largest_stretch_of_row(m, i, true);
}

std::vector<double> breakable_stretch_ratio(const Model& m) {
  const NodeSet& ns = m.nodes;
  std::vector<double> r(ns.size(), 0.0);
#pragma omp parallel for schedule(guided, 64)
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || !(ns.critical_stretch[i] > 0.0)) continue;
    const double s = largest_breakable_stretch(m, static_cast<std::uint32_t>(i));
    if (std::isfinite(s)) r[i] = s / ns.critical_stretch[i];
  }
  return r;
}

}  // namespace periadapt
