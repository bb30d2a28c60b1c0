#include "discretize/surface_correction.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace periadapt {

void apply_surface_correction(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape,
                              double M) {
  const int D = ns.dim;
  const std::size_t n = ns.size();
  std::vector<double> g(3 * n, 1.0);
  const double w_classical = 0.5 * M;  // unit strain
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    double w[3] = {0, 0, 0};
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      const double L = bf.length(k);
      const double wt = influence(shape, std::min(1.0, L / ns.horizon[i])) *
                        std::abs(static_cast<double>(bf.beta[k])) * ns.volume[j] * L;
      for (int d = 0; d < D; ++d) {
        const double nd = (ns.x[d][j] - ns.x[d][i]) / L;  // bond stretch under unit strain: n_d^2
        w[d] += wt * nd * nd * nd * nd;
      }
    }
    for (int d = 0; d < D; ++d) {
      const double wpd = 0.25 * ns.micromodulus[i] * w[d];
      g[3 * i + d] = wpd > 0 ? w_classical / wpd : 1.0;
    }
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      const double L = bf.length(k);
      double q = 0;
      for (int d = 0; d < D; ++d) {
        const double nd = (ns.x[d][j] - ns.x[d][i]) / L;
        const double gbar = 0.5 * (g[3 * i + d] + g[3 * j + d]);
        q += (nd / gbar) * (nd / gbar);
      }
      bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) / std::sqrt(q));
    }
  }
}

}  // namespace periadapt
