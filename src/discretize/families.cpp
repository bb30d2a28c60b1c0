#include "discretize/families.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/cell_grid.hpp"

namespace periadapt {

BondFamilies build_families(const NodeSet& nodes, const QuadratureSpec& quad) {
  const std::size_t n = nodes.size();
  BondFamilies fam;
  fam.offsets.assign(n + 1, 0);
  if (n == 0) return fam;
  double hmax = 0, dxmax = 0;
  for (std::size_t i = 0; i < n; ++i) {
    hmax = std::max(hmax, nodes.horizon[i]);
    dxmax = std::max(dxmax, nodes.spacing[i]);
  }
  hmax = quadrature_search_radius(quad.rule, nodes.dim, hmax, dxmax);
  CellGrid grid(nodes.dim, {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()}, n, hmax);

  struct Chunk {
    std::vector<std::uint32_t> nbr;
    std::vector<double> len;
    std::vector<float> beta;
  };
  const int nthreads = omp_get_max_threads();
  std::vector<Chunk> chunks(static_cast<std::size_t>(nthreads));
  std::vector<std::uint64_t> counts(n, 0);

#pragma omp parallel num_threads(nthreads)
  {
    const int t = omp_get_thread_num();
    const int nt = omp_get_num_threads();
    const std::size_t lo = n * t / nt, hi = n * (t + 1) / nt;
    Chunk& ch = chunks[static_cast<std::size_t>(t)];
    ch.nbr.reserve((hi - lo) * 64);
    ch.len.reserve((hi - lo) * 64);
    ch.beta.reserve((hi - lo) * 64);
    for (std::size_t i = lo; i < hi; ++i) {
      if (!(nodes.flags[i] & kActive)) continue;
      const std::array<double, 3> p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
      const double delta = nodes.horizon[i];
      const double radius = quadrature_search_radius(quad.rule, nodes.dim, delta, nodes.spacing[i]);
      const std::size_t first = ch.nbr.size();
      // Nodes exactly on the horizon (m integer) are included whatever the rounding.
      grid.for_each_within(p, radius * (1 + 1e-12), [&](std::uint32_t j, double d2) {
        if (j == i || !(nodes.flags[j] & kActive)) return;
        const double xi = std::sqrt(d2);
        double b;
        if (quad.rule == Quadrature::Subcell) {
          const std::array<double, 3> off{nodes.x[0][j] - p[0], nodes.x[1][j] - p[1],
                                          nodes.x[2][j] - p[2]};
          b = subcell_fraction(nodes.dim, off, delta, nodes.spacing[j], quad.lattice_rotation);
        } else {
          b = partial_volume_factor(quad.rule, std::min(xi, delta), delta, nodes.spacing[j]);
        }
        if (b <= 0) return;
        ch.nbr.push_back(j);
        ch.len.push_back(1.0 / xi);
        ch.beta.push_back(static_cast<float>(b));
      });
      // Sorted families: deterministic and friendlier to the caches in the force loop.
      const std::size_t cnt = ch.nbr.size() - first;
      if (cnt > 1) {
        std::vector<std::size_t> perm(cnt);
        for (std::size_t k = 0; k < cnt; ++k) perm[k] = first + k;
        std::sort(perm.begin(), perm.end(),
                  [&](std::size_t a, std::size_t b) { return ch.nbr[a] < ch.nbr[b]; });
        std::vector<std::uint32_t> tn(cnt);
        std::vector<double> tl(cnt);
        std::vector<float> tb(cnt);
        for (std::size_t k = 0; k < cnt; ++k) {
          tn[k] = ch.nbr[perm[k]];
          tl[k] = ch.len[perm[k]];
          tb[k] = ch.beta[perm[k]];
        }
        std::copy(tn.begin(), tn.end(), ch.nbr.begin() + static_cast<long>(first));
        std::copy(tl.begin(), tl.end(), ch.len.begin() + static_cast<long>(first));
        std::copy(tb.begin(), tb.end(), ch.beta.begin() + static_cast<long>(first));
      }
      counts[i] = cnt;
    }
  }
  for (std::size_t i = 0; i < n; ++i) fam.offsets[i + 1] = fam.offsets[i] + counts[i];
  const std::size_t total = fam.offsets[n];
  fam.neighbor.resize(total);
  fam.inv_length.resize(total);
  fam.beta.resize(total);
#pragma omp parallel num_threads(nthreads)
  {
    const int t = omp_get_thread_num();
    const int nt = omp_get_num_threads();
    const std::size_t lo = n * t / nt;
    const Chunk& ch = chunks[static_cast<std::size_t>(t)];
    const std::size_t dst = fam.offsets[lo];
    std::copy(ch.nbr.begin(), ch.nbr.end(), fam.neighbor.begin() + static_cast<long>(dst));
    std::copy(ch.len.begin(), ch.len.end(), fam.inv_length.begin() + static_cast<long>(dst));
    std::copy(ch.beta.begin(), ch.beta.end(), fam.beta.begin() + static_cast<long>(dst));
  }
  return fam;
}

void update_damage_weights(NodeSet& nodes, const BondFamilies& bonds) {
  const std::size_t n = nodes.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double total = 0, broken = 0;
    for (std::uint64_t k = bonds.begin(i); k < bonds.end(i); ++k) {
      const double w = std::abs(static_cast<double>(bonds.beta[k])) * nodes.volume[bonds.neighbor[k]];
      total += w;
      if (!BondFamilies::intact(bonds.beta[k])) broken += w;
    }
    nodes.family_weight[i] = total;
    nodes.broken_weight[i] = broken;
  }
}

}  // namespace periadapt
