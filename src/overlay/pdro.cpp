#include "overlay/pdro.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include "core/visible_gradient.hpp"
#include "overlay/pddo.hpp"

namespace periadapt {

namespace {

using P3 = std::array<double, 3>;

// Current positions of the virtual points `at` by the PDDO over the active nodes within the
// horizons of both I and J (the paper's sampling; damaged ones included), plus I and J; false
// when the moment matrix is singular. (Over the union of the two families the fit smoothed the
// crack-tip field more: with the Gaussian weight SENT at n = 5 failed 24% above the plain run
// instead of 14%.)
bool positions_by_pddo(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::size_t j,
                       const std::vector<P3>& at, std::vector<P3>& y, PddoWeight weight) {
  const int D = ns.dim;
  // Rows are sorted by neighbour id (families.cpp), so the common members come out of one merge.
  std::vector<std::uint32_t> ids;
  ids.reserve(std::min(bf.end(i) - bf.begin(i), bf.end(j) - bf.begin(j)) + 2);
  std::set_intersection(bf.neighbor.begin() + static_cast<long>(bf.begin(i)),
                        bf.neighbor.begin() + static_cast<long>(bf.end(i)),
                        bf.neighbor.begin() + static_cast<long>(bf.begin(j)),
                        bf.neighbor.begin() + static_cast<long>(bf.end(j)), std::back_inserter(ids));
  ids.push_back(static_cast<std::uint32_t>(i));
  ids.push_back(static_cast<std::uint32_t>(j));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::erase_if(ids, [&](std::uint32_t p) { return !(ns.flags[p] & kActive); });
  std::vector<PddoPoint> pts;
  pts.reserve(ids.size());
  for (std::uint32_t p : ids) pts.push_back({{ns.x[0][p], ns.x[1][p], ns.x[2][p]}, ns.volume[p]});
  std::vector<double> c;
  y.resize(at.size());
  for (std::size_t v = 0; v < at.size(); ++v) {
    if (!pddo_weights(D, at[v], pts, ns.horizon[i], c, weight)) return false;
    y[v] = at[v];
    for (std::size_t m = 0; m < ids.size(); ++m)
      for (int d = 0; d < D; ++d) y[v][static_cast<std::size_t>(d)] += c[m] * ns.u[static_cast<std::size_t>(d)][ids[m]];
  }
  return true;
}

// Current positions by the visible linear fit (PIM) of the nearer end node (I for the points in
// the first half of the bond, J for the others).
void positions_by_pim(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::size_t j,
                      const std::vector<P3>& at, std::vector<P3>& y, const float* beta) {
  const int D = ns.dim;
  double GI[3][3], GJ[3][3];
  fit_gradient(ns, bf, static_cast<std::uint32_t>(i), ns.u, GI, beta);
  fit_gradient(ns, bf, static_cast<std::uint32_t>(j), ns.u, GJ, beta);
  y.resize(at.size());
  for (std::size_t v = 0; v < at.size(); ++v) {
    double dI = 0, dJ = 0;
    for (int d = 0; d < D; ++d) {
      dI += std::pow(at[v][static_cast<std::size_t>(d)] - ns.x[static_cast<std::size_t>(d)][i], 2);
      dJ += std::pow(at[v][static_cast<std::size_t>(d)] - ns.x[static_cast<std::size_t>(d)][j], 2);
    }
    const bool near_i = dI <= dJ;
    const std::size_t e = near_i ? i : j;
    const auto& G = near_i ? GI : GJ;
    y[v] = at[v];
    for (int d = 0; d < D; ++d) {
      double u = ns.u[static_cast<std::size_t>(d)][e];
      for (int a = 0; a < D; ++a)
        u += G[d][a] * (at[v][static_cast<std::size_t>(a)] - ns.x[static_cast<std::size_t>(a)][e]);
      y[v][static_cast<std::size_t>(d)] += u;
    }
  }
}

}  // namespace

bool pdro_bond_breaks(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::uint64_t k,
                      double s0, const PdroSpec& spec, double thermal_strain) {
  const int D = ns.dim;
  const std::size_t j = bf.neighbor[k];
  if (spec.region &&
      !spec.region->contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, 1e-9 * ns.spacing[i]))
    return true;
  spec.counters->checks.fetch_add(1, std::memory_order_relaxed);
  const double L = bf.length(k), dxp = std::min(L, ns.spacing[i]) / spec.n;
  const P3 I{ns.x[0][i], ns.x[1][i], ns.x[2][i]}, J{ns.x[0][j], ns.x[1][j], ns.x[2][j]};
  // Sub-pairs as [start, end] distances from I along the bond; 0 and L are the real nodes.
  std::vector<std::array<double, 2>> pairs;
  if (spec.sampling == PdroSampling::ThreePairs) {
    pairs = {{0.0, dxp}, {0.5 * (L - dxp), 0.5 * (L + dxp)}, {L - dxp, L}};
  } else {
    // Consecutive sub-pairs from I to J (the last one ends on J), so wherever a crack crosses the
    // bond one sub-pair straddles it.
    const auto count = static_cast<std::size_t>(std::ceil(L / dxp - 1e-9));
    for (std::size_t q = 0; q < count; ++q) {
      const double a = std::min(static_cast<double>(q) * dxp, L - dxp);
      pairs.push_back({a, a + dxp});
    }
  }
  // Distinct interior positions, interpolated once each.
  std::vector<double> ts;
  for (const auto& pr : pairs)
    for (double t : pr)
      if (t > 1e-12 * L && t < L * (1 - 1e-12)) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end(), [&](double a, double b) { return b - a < 1e-12 * L; }),
           ts.end());
  std::vector<P3> at(ts.size()), y;
  for (std::size_t v = 0; v < ts.size(); ++v)
    for (int d = 0; d < 3; ++d)
      at[v][static_cast<std::size_t>(d)] =
          I[static_cast<std::size_t>(d)] + ts[v] / L * (J[static_cast<std::size_t>(d)] - I[static_cast<std::size_t>(d)]);
  if (spec.interpolation == PdroInterpolation::Pim) {
    const std::vector<float>& vb = *spec.visible_beta;
    positions_by_pim(ns, bf, i, j, at, y, vb.size() == bf.beta.size() ? vb.data() : nullptr);
  } else if (!positions_by_pddo(ns, bf, i, j, at, y, spec.weight)) {
    spec.counters->breaks.fetch_add(1, std::memory_order_relaxed);
    return true;  // no overlay possible: plain rule
  }
  P3 yI{0, 0, 0}, yJ{0, 0, 0};
  for (int d = 0; d < D; ++d) {
    yI[static_cast<std::size_t>(d)] = ns.cur[4 * i + static_cast<std::size_t>(d)];
    yJ[static_cast<std::size_t>(d)] = ns.cur[4 * j + static_cast<std::size_t>(d)];
  }
  auto position = [&](double t) -> const P3& {
    if (t <= 1e-12 * L) return yI;
    if (t >= L * (1 - 1e-12)) return yJ;
    const auto it = std::lower_bound(ts.begin(), ts.end(), t - 1e-12 * L);
    return y[static_cast<std::size_t>(it - ts.begin())];
  };
  auto strain = [&](const P3& a, const P3& b) {
    double r2 = 0;
    for (int d = 0; d < D; ++d) r2 += std::pow(b[static_cast<std::size_t>(d)] - a[static_cast<std::size_t>(d)], 2);
    return std::sqrt(r2) / dxp - 1.0 - thermal_strain;
  };
  double smax = -std::numeric_limits<double>::infinity();
  for (const auto& pr : pairs) smax = std::max(smax, strain(position(pr[0]), position(pr[1])));
  const bool breaks = smax > s0 * std::sqrt(spec.n);
  if (breaks) spec.counters->breaks.fetch_add(1, std::memory_order_relaxed);
  return breaks;
}

}  // namespace periadapt
