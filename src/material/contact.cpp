#include "material/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/cell_grid.hpp"
#include "core/node_set.hpp"

namespace periadapt {

namespace {

// The active nodes' current positions in a cell list whose cells hold every contact partner of a
// node within the neighbouring cells.
struct ContactIndex {
  std::array<std::vector<double>, 3> y;
  std::vector<std::uint32_t> active;
  double largest_spacing = 0;
  std::optional<CellGrid> grid;

  ContactIndex(const ContactSpec& spec, const NodeSet& ns) {
    const std::size_t n = ns.size();
    for (auto& c : y) c.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      active.push_back(static_cast<std::uint32_t>(i));
      largest_spacing = std::max(largest_spacing, ns.spacing[i]);
      for (int d = 0; d < ns.dim; ++d) y[d][i] = ns.cur[4 * i + d];
    }
    if (!active.empty())
      grid.emplace(ns.dim, std::array<const double*, 3>{y[0].data(), y[1].data(), y[2].data()},
                   active, spec.spacing_factor * largest_spacing);
  }

  // Calls fn(j, r, overlap) for every partner j of node i in contact: r < d_ij, overlap d_ij - r.
  template <class Fn>
  void for_each_contact(const ContactSpec& spec, const NodeSet& ns, std::size_t i, Fn&& fn) const {
    const double reach = spec.spacing_factor * 0.5 * (ns.spacing[i] + largest_spacing);
    const std::array<double, 3> p{y[0][i], y[1][i], y[2][i]};
    grid->for_each_within(p, reach, [&](std::uint32_t j, double r2) {
      if (j == i || !(r2 > 0)) return;
      double X2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        const double t = ns.x[d][j] - ns.x[d][i];
        X2 += t * t;
      }
      const double dij = std::min(spec.distance_factor * std::sqrt(X2),
                                  spec.spacing_factor * 0.5 * (ns.spacing[i] + ns.spacing[j]));
      const double r = std::sqrt(r2);
      if (r < dij) fn(j, r, dij - r);
    });
  }
};

double pair_stiffness(const ContactSpec& spec, const NodeSet& ns, std::size_t i, std::size_t j) {
  return spec.stiffness_factor * 0.5 *
         (ns.micromodulus[i] / ns.horizon[i] + ns.micromodulus[j] / ns.horizon[j]) *
         ns.volume[i] * ns.volume[j];
}

}  // namespace

void add_contact_forces(const ContactSpec& spec, NodeSet& ns, const std::vector<std::uint32_t>* rows,
                        std::vector<double>* W) {
  const ContactIndex index(spec, ns);
  if (!index.grid) return;
  const std::vector<std::uint32_t>& list = rows ? *rows : index.active;
#pragma omp parallel for schedule(guided, 64)
  for (std::size_t r = 0; r < list.size(); ++r) {
    const std::size_t i = list[r];
    if (!(ns.flags[i] & kActive)) continue;
    std::array<double, 3> f{0, 0, 0};
    double w = 0;
    index.for_each_contact(spec, ns, i, [&](std::uint32_t j, double dist, double overlap) {
      const double k = pair_stiffness(spec, ns, i, j);
      const double push = k * overlap / dist;  // F / r: along (y_i - y_j)
      for (int d = 0; d < ns.dim; ++d) f[d] += push * (index.y[d][i] - index.y[d][j]);
      w += 0.25 * k * overlap * overlap;
    });
    const double inv_v = 1.0 / ns.volume[i];
    for (int d = 0; d < ns.dim; ++d) ns.f[d][i] += f[d] * inv_v;
    if (W) (*W)[i] += w * inv_v;
  }
}

void add_contact_energy(const ContactSpec& spec, const NodeSet& ns, std::vector<double>& W) {
  const ContactIndex index(spec, ns);
  if (!index.grid) return;
#pragma omp parallel for schedule(guided, 64)
  for (std::size_t r = 0; r < index.active.size(); ++r) {
    const std::size_t i = index.active[r];
    double w = 0;
    index.for_each_contact(spec, ns, i, [&](std::uint32_t j, double, double overlap) {
      w += 0.25 * pair_stiffness(spec, ns, i, j) * overlap * overlap;
    });
    W[i] += w / ns.volume[i];
  }
}

double contact_stiffness_bound(const ContactSpec& spec, const NodeSet& ns, std::size_t i) {
  // Volume of the contact ball of radius spacing_factor h_i, in cells of node i's size: the most
  // partner volume a node can meet (more, finer partners share the same room).
  const double R = spec.spacing_factor;
  const double cells = ns.dim == 1   ? 2 * R
                       : ns.dim == 2 ? std::numbers::pi * R * R
                                     : 4.0 / 3.0 * std::numbers::pi * R * R * R;
  return spec.stiffness_factor * ns.micromodulus[i] / ns.horizon[i] * cells * ns.volume[i];
}

}  // namespace periadapt
