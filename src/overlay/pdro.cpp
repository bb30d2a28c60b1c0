#include "overlay/pdro.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "overlay/pddo.hpp"

namespace periadapt {

bool pdro_bond_breaks(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::uint64_t k,
                      double s0, const PdroSpec& spec) {
  const int D = ns.dim;
  const std::size_t j = bf.neighbor[k];
  if (spec.region &&
      !spec.region->contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, 1e-9 * ns.spacing[i]))
    return true;
  // Material points of both families and the two ends (ids sorted, unique).
  std::vector<std::uint32_t> ids;
  ids.reserve(bf.end(i) - bf.begin(i) + bf.end(j) - bf.begin(j) + 2);
  ids.push_back(static_cast<std::uint32_t>(i));
  ids.push_back(static_cast<std::uint32_t>(j));
  for (std::uint64_t q = bf.begin(i); q < bf.end(i); ++q) ids.push_back(bf.neighbor[q]);
  for (std::uint64_t q = bf.begin(j); q < bf.end(j); ++q) ids.push_back(bf.neighbor[q]);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<PddoPoint> pts;
  pts.reserve(ids.size());
  for (std::uint32_t p : ids)
    if (ns.flags[p] & kActive) pts.push_back({{ns.x[0][p], ns.x[1][p], ns.x[2][p]}, ns.volume[p]});

  const double L = bf.length(k), dxp = L / spec.n;
  std::array<double, 3> e{0, 0, 0}, I{ns.x[0][i], ns.x[1][i], ns.x[2][i]},
      J{ns.x[0][j], ns.x[1][j], ns.x[2][j]};
  for (int d = 0; d < D; ++d) e[static_cast<std::size_t>(d)] = (J[static_cast<std::size_t>(d)] - I[static_cast<std::size_t>(d)]) / L;
  auto along = [&](const std::array<double, 3>& from, double t) {
    std::array<double, 3> p = from;
    for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] += t * e[static_cast<std::size_t>(d)];
    return p;
  };
  const double half = 0.5 * L;
  const std::array<double, 3> vi = along(I, dxp), vj = along(J, -dxp), vip = along(I, half - 0.5 * dxp),
                              vjp = along(I, half + 0.5 * dxp);
  // Current position of a virtual point: x + PDDO-interpolated displacement.
  std::vector<double> c;
  auto current = [&](const std::array<double, 3>& at, std::array<double, 3>& y) {
    if (!pddo_weights(D, at, pts, ns.horizon[i], c)) return false;
    y = at;
    std::size_t m = 0;
    for (std::uint32_t p : ids) {
      if (!(ns.flags[p] & kActive)) continue;
      for (int d = 0; d < D; ++d)
        y[static_cast<std::size_t>(d)] += c[m] * (ns.cur[4 * p + static_cast<std::size_t>(d)] - ns.x[static_cast<std::size_t>(d)][p]);
      ++m;
    }
    return true;
  };
  std::array<double, 3> yi, yj, yip, yjp, yI{0, 0, 0}, yJ{0, 0, 0};
  if (!current(vi, yi) || !current(vj, yj) || !current(vip, yip) || !current(vjp, yjp))
    return true;  // no overlay possible: plain rule
  for (int d = 0; d < D; ++d) {
    yI[static_cast<std::size_t>(d)] = ns.cur[4 * i + static_cast<std::size_t>(d)];
    yJ[static_cast<std::size_t>(d)] = ns.cur[4 * j + static_cast<std::size_t>(d)];
  }
  auto strain = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double r2 = 0;
    for (int d = 0; d < D; ++d) r2 += std::pow(b[static_cast<std::size_t>(d)] - a[static_cast<std::size_t>(d)], 2);
    return std::sqrt(r2) / dxp - 1.0;
  };
  const double smax = std::max({strain(yI, yi), strain(yip, yjp), strain(yj, yJ)});
  return smax > s0 * std::sqrt(spec.n);
}

}  // namespace periadapt
