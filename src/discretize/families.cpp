#include "discretize/families.hpp"

#include <algorithm>
#include <cmath>

#include "core/cell_grid.hpp"

namespace periadapt {

BondFamilies build_families(const NodeSet& nodes, const QuadratureSpec& quad,
                            const BondFamilies* keep, const std::vector<char>* rebuild) {
  BondFamilies fam;
  build_families_into(fam, nodes, quad, keep, rebuild);
  return fam;
}

void build_families_into(BondFamilies& fam, const NodeSet& nodes, const QuadratureSpec& quad,
                         const BondFamilies* keep, const std::vector<char>* rebuild) {
  const std::size_t n = nodes.size();
  fam.offsets.assign(n + 1, 0);
  fam.t_offsets.clear();
  fam.t_owner.clear();
  fam.t_bond.clear();
  if (n == 0) {
    fam.neighbor.clear();
    fam.inv_length.clear();
    fam.beta.clear();
    return;
  }
  double hmax = 0, dxmax = 0;
  for (std::size_t i = 0; i < n; ++i) {
    hmax = std::max(hmax, nodes.horizon[i]);
    dxmax = std::max(dxmax, nodes.spacing[i]);
  }
  hmax = quadrature_search_radius(quad.rule, nodes.dim, hmax, dxmax);
  auto copied = [&](std::size_t i) {
    return keep && rebuild && i < keep->num_nodes() && !(*rebuild)[i];
  };
  CellGrid grid(nodes.dim, {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()}, n, hmax);

  // Calls visit(j, 1/xi, beta) for every family member of node i, in a fixed order.
  auto visit_family = [&](std::size_t i, auto&& visit) {
    const std::array<double, 3> p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
    const double delta = nodes.horizon[i];
    const double radius = quadrature_search_radius(quad.rule, nodes.dim, delta, nodes.spacing[i]);
    // Nodes exactly on the horizon (m integer) are included whatever the rounding.
    grid.for_each_within(p, radius * (1 + 1e-12), [&](std::uint32_t j, double d2) {
      if (j == i || !(nodes.flags[j] & kActive)) return;
      const double xi = std::sqrt(d2);
      double b;
      if (quad.rule == Quadrature::Subcell || quad.rule == Quadrature::IpaHybrid) {
        const std::array<double, 3> off{nodes.x[0][j] - p[0], nodes.x[1][j] - p[1],
                                        nodes.x[2][j] - p[2]};
        b = subcell_fraction(nodes.dim, off, delta, nodes.spacing[j], quad.lattice_rotation);
      } else {
        b = partial_volume_factor(quad.rule, std::min(xi, delta), delta, nodes.spacing[j]);
      }
      if (b > 0) visit(j, 1.0 / xi, static_cast<float>(b));
    });
  };

  // Two passes (count, then fill in place) so that the only bond-sized memory ever allocated is
  // the final CSR arrays: no per-thread buffers, no copy.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(nodes.flags[i] & kActive)) continue;
    if (copied(i)) {
      fam.offsets[i + 1] = keep->end(i) - keep->begin(i);
      continue;
    }
    std::uint64_t cnt = 0;
    visit_family(i, [&](std::uint32_t, double, float) { ++cnt; });
    fam.offsets[i + 1] = cnt;
  }
  for (std::size_t i = 0; i < n; ++i) fam.offsets[i + 1] += fam.offsets[i];
  const std::size_t total = fam.offsets[n];
  // Reused storage (refinement events) grows with headroom and without copying stale contents,
  // so that a run of events touches fresh memory only now and then.
  auto fit = [total](auto& v) {
    if (v.capacity() < total) {
      v.clear();
      v.shrink_to_fit();
      v.reserve(total + total / 16);
    }
    v.resize(total);
  };
  fit(fam.neighbor);
  fit(fam.inv_length);
  fit(fam.beta);

  struct Entry {
    std::uint32_t j;
    float beta;
    double inv_len;
  };
#pragma omp parallel
  {
    std::vector<Entry> scratch;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      if (!(nodes.flags[i] & kActive)) continue;
      if (copied(i)) {
        const std::uint64_t b = keep->begin(i), e = keep->end(i), o = fam.offsets[i];
        std::copy(keep->neighbor.begin() + static_cast<long>(b), keep->neighbor.begin() + static_cast<long>(e),
                  fam.neighbor.begin() + static_cast<long>(o));
        std::copy(keep->inv_length.begin() + static_cast<long>(b), keep->inv_length.begin() + static_cast<long>(e),
                  fam.inv_length.begin() + static_cast<long>(o));
        std::copy(keep->beta.begin() + static_cast<long>(b), keep->beta.begin() + static_cast<long>(e),
                  fam.beta.begin() + static_cast<long>(o));
        continue;
      }
      scratch.clear();
      visit_family(i, [&](std::uint32_t j, double il, float b) { scratch.push_back({j, b, il}); });
      // Sorted families: independent of the cell layout and friendlier to the caches.
      std::sort(scratch.begin(), scratch.end(),
                [](const Entry& a, const Entry& b) { return a.j < b.j; });
      std::size_t k = fam.offsets[i];
      for (const Entry& e : scratch) {
        fam.neighbor[k] = e.j;
        fam.inv_length[k] = e.inv_len;
        fam.beta[k] = e.beta;
        ++k;
      }
    }
  }
}

void build_transpose(BondFamilies& bf) {
  const std::size_t n = bf.num_nodes();
  bf.t_offsets.assign(n + 1, 0);
  for (std::uint32_t j : bf.neighbor) ++bf.t_offsets[j + 1];
  for (std::size_t i = 0; i < n; ++i) bf.t_offsets[i + 1] += bf.t_offsets[i];
  bf.t_owner.resize(bf.num_bonds());
  bf.t_bond.resize(bf.num_bonds());
  std::vector<std::uint64_t> fill(bf.t_offsets.begin(), bf.t_offsets.end() - 1);
  // Owners in increasing order, so each transposed row is sorted by owner (deterministic sums).
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint64_t q = fill[bf.neighbor[k]]++;
      bf.t_owner[q] = static_cast<std::uint32_t>(i);
      bf.t_bond[q] = k;
    }
}

void mark_unbreakable_bonds(const NodeSet& ns, BondFamilies& bf, const std::vector<char>* rows) {
  const std::size_t n = ns.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    if (!rows || (*rows)[i])
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
      if ((ns.flags[i] | ns.flags[bf.neighbor[k]]) & kNoFail)
        bf.inv_length[k] = -std::abs(bf.inv_length[k]);
}

void update_damage_weights(NodeSet& nodes, const BondFamilies& bonds,
                           const std::vector<char>* rows) {
  const std::size_t n = nodes.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (rows && !(*rows)[i]) continue;
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
