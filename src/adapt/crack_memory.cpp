#include "adapt/crack_memory.hpp"

#include "discretize/interface_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "core/cell_grid.hpp"
#include "discretize/partial_volume.hpp"
#include "discretize/surface_correction.hpp"
#include "parallel/held_rows.hpp"

namespace periadapt {

namespace {

// Directed: a bond of i's family to j (its state can differ from j's bond to i when the two
// critical stretches or no-fail flags differ).
std::uint64_t pair_key(std::uint32_t owner, std::uint32_t other) {
  return (static_cast<std::uint64_t>(owner) << 32) | other;
}


}  // namespace

CrackMemory remember_cracks(const Model& m, const std::vector<char>& vanishing,
                            const std::vector<char>* refined) {
  const NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  CrackMemory mem;
  const int D = ns.dim;
  if (D == 1) return mem;  // a 1D bar has no crack paths to carry over
  // Only the rows of the nodes that vanish or get new nodes around them: a facet stands for a
  // broken bond with such an end, in either direction (rows are sorted by neighbour id, so the
  // reverse bond is found by bisection).
  auto broken = [&](std::size_t a, std::uint32_t b) {
    const auto first = bf.neighbor.begin() + static_cast<long>(bf.begin(a));
    const auto last = bf.neighbor.begin() + static_cast<long>(bf.end(a));
    const auto it = std::lower_bound(first, last, b);
    return it != last && *it == b &&
           !BondFamilies::intact(bf.beta[static_cast<std::size_t>(it - bf.neighbor.begin())]);
  };
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || !(vanishing[i] || (refined && (*refined)[i]))) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      if (BondFamilies::intact(bf.beta[k]) && !broken(j, static_cast<std::uint32_t>(i))) continue;
      const Vec3 xi{ns.x[0][i], ns.x[1][i], D == 3 ? ns.x[2][i] : 0.0},
          xj{ns.x[0][j], ns.x[1][j], D == 3 ? ns.x[2][j] : 0.0};
      // Pre-crack bonds are cut again geometrically after the rebuild.
      bool precrack = false;
      for (const PreCrack& c : m.cracks)
        precrack = precrack || (c.planar3d ? bond_crosses_quad(xi, xj, c.points)
                                           : bond_crosses_segment(xi, xj, c.points[0], c.points[1]));
      if (precrack) continue;
      const Vec3 mid = scale(add(xi, xj), 0.5), e = scale(sub(xj, xi), 1.0 / norm(sub(xj, xi)));
      // Short facets: the bond says the crack crosses it, not where nor how it is oriented.
      const double half = 0.25 * std::min(ns.spacing[i], ns.spacing[j]);
      Facet f;
      if (D == 2) {
        const Vec3 t{-e[1] * half, e[0] * half, 0};
        f.a = sub(mid, t);
        f.b = add(mid, t);
      } else {
        // A square across the bond: two unit vectors normal to it.
        const Vec3 axis = std::abs(e[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        Vec3 u = cross(e, axis);
        u = scale(u, half / norm(u));
        const Vec3 w = scale(cross(e, u), 1.0);  // |e x u| = |u|
        f.in3d = true;
        f.quad = {sub(sub(mid, u), w), sub(add(mid, u), w), add(add(mid, u), w), add(sub(mid, u), w)};
      }
      mem.facets.push_back(f);
    }
  }
  return mem;
}

std::vector<std::uint32_t> rebuild_families(Model& m, const CrackMemory& mem,
                                            std::size_t n_before, const std::vector<char>& changed,
                                            bool appended_only) {
  NodeSet& ns = m.nodes;
  BondFamilies& bf = m.bonds;
  const int D = ns.dim;
  // The window: changed nodes and every active node whose search radius reaches one of them.
  std::vector<char> rebuild(ns.size(), 0);
  const bool corrected = m.surface_correction != SurfaceCorrection::None;
  const bool global = std::getenv("PERIADAPT_GLOBAL_REBUILD") != nullptr ||
                      (corrected && !m.window_surface_correction);
  // A surface correction multiplies the quadrature's factors: rows it corrects again must start
  // from a fresh search, not from their patched (corrected) entries.
  if (corrected) appended_only = false;
  double member_reach = 0;  // no member lies farther from its row (after the event)
  if (!global) {
    // Largest search radius of any active node (the radius grows with both arguments).
    double hmax = 0, dxmax = 0;
    std::vector<std::uint32_t> ch;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (ns.flags[i] & kActive) {
        hmax = std::max(hmax, ns.horizon[i]);
        dxmax = std::max(dxmax, ns.spacing[i]);
      }
      if (i < changed.size() && changed[i]) ch.push_back(static_cast<std::uint32_t>(i));
    }
    const double rmax = std::max(quadrature_search_radius(m.quadrature.rule, D, hmax, dxmax), 1e-300);
    member_reach = rmax * (1 + 1e-9);
    // A cell list over the nodes near the changed ones only: the event's cost follows its region.
    CellGrid grid(D, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()},
                  active_nodes_near(ns, ch, rmax * (1 + 1e-9)), rmax);
    for (std::uint32_t c : ch) {
      rebuild[c] = 1;
      grid.for_each_within({ns.x[0][c], ns.x[1][c], ns.x[2][c]}, rmax * (1 + 1e-9),
                           [&](std::uint32_t j, double d2) {
                             if (!(ns.flags[j] & kActive) || rebuild[j]) return;
                             const double rj = quadrature_search_radius(
                                 m.quadrature.rule, D, ns.horizon[j], std::max(ns.spacing[j], ns.spacing[c]));
                             if (d2 <= rj * rj * (1 + 1e-9)) rebuild[j] = 1;
                           });
    }
  }
  if (m.partition.rows_held) {
    // Held bond rows (a distributed run): every rank searches the window again, from its rows'
    // old contents.
    if (global) throw std::logic_error("held bond rows cannot be rebuilt globally");
    std::vector<std::uint32_t> rows;
    for (std::size_t i = 0; i < std::min(n_before, bf.num_nodes()); ++i)
      if (rebuild[i]) rows.push_back(static_cast<std::uint32_t>(i));
    publish_rows(m.partition, bf, rows);
  }
  // Broken bonds between surviving nodes, read from the current families for the rows about to
  // be searched again (copied rows keep their states as they are).
  std::vector<std::uint64_t> broken_pairs;
  for (std::size_t i = 0; i < std::min(n_before, bf.num_nodes()); ++i) {
    if (!rebuild[i] && !global) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
      if (!BondFamilies::intact(bf.beta[k]))
        broken_pairs.push_back(pair_key(static_cast<std::uint32_t>(i), bf.neighbor[k]));
  }
  std::sort(broken_pairs.begin(), broken_pairs.end());
  // History laws: the rows searched again get their surviving bonds' histories back.
  std::vector<std::pair<std::uint64_t, double>> histories;
  if (bf.keeps_state) {
    for (std::size_t i = 0; i < std::min(n_before, bf.num_nodes()); ++i) {
      if (!rebuild[i] && !global) continue;
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
        if (BondFamilies::intact(bf.beta[k]) && bf.state[k] != 0.0)
          histories.emplace_back(pair_key(static_cast<std::uint32_t>(i), bf.neighbor[k]), bf.state[k]);
    }
    std::sort(histories.begin(), histories.end());
  }
  if (global) {
    const bool keeps_state = bf.keeps_state;
    bf = build_families(ns, m.quadrature);
    if (keeps_state) bf.enable_state();
  }
  else if (appended_only) {
    // Unchanged old nodes keep their old neighbours (those still active) and bond states.
    std::vector<char> patch(ns.size(), 0);
    for (std::size_t i = 0; i < n_before; ++i)
      patch[i] = rebuild[i] && !(i < changed.size() && changed[i]);
    rebuild_rows(bf, ns, m.quadrature, rebuild, &patch);
  } else {
    rebuild_rows(bf, ns, m.quadrature, rebuild);
  }
  if (global) std::fill(rebuild.begin(), rebuild.end(), 1);
  const double modulus = p_wave_modulus(D, m.material.plane, m.material.E, m.material.nu);
  // Rows around the window whose corrected factors the event changed.
  std::vector<std::uint32_t> recorrected;
  if (global)
    apply_surface_correction(ns, bf, m.material.shape, modulus, m.surface_correction,
                             m.formulation.state_based(), block_uniaxial_moduli(m));
  else
    recorrected = correct_surface_window(ns, bf, m.quadrature, m.material.shape, modulus,
                                         m.surface_correction, m.formulation.state_based(),
                                         block_uniaxial_moduli(m), rebuild);
  if (m.interface_fit) fit_interface_quadrature(ns, bf, m.material.shape, rebuild);
  apply_precracks(ns, bf, m.cracks, &rebuild);
  CellGrid* fgrid = nullptr;
  std::vector<double> fx[3];
  double reach = 0;
  if (!mem.facets.empty()) {
    for (auto& v : fx) v.resize(mem.facets.size());
    for (std::size_t f = 0; f < mem.facets.size(); ++f) {
      const Vec3 c = mem.facets[f].centre();
      for (int d = 0; d < 3; ++d) fx[d][f] = c[d];
    }
    for (const Facet& f : mem.facets) reach = std::max(reach, f.reach());
  }
  double hmax_all = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) hmax_all = std::max(hmax_all, ns.horizon[i]);
  CellGrid facet_grid(D, {fx[0].data(), fx[1].data(), fx[2].data()}, mem.facets.size(),
                      std::max(reach + 0.5 * hmax_all, 1e-300));
  if (!mem.facets.empty()) fgrid = &facet_grid;
  // Rows are independent (each writes its own bond states); the facet searches dominate.
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!rebuild[i]) continue;  // copied rows keep their bond states
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      if (!BondFamilies::intact(bf.beta[k])) continue;
      bool broken = false;
      if (i < n_before && j < n_before) {
        const std::uint64_t key = pair_key(static_cast<std::uint32_t>(i), j);
        broken = std::binary_search(broken_pairs.begin(), broken_pairs.end(), key);
        if (!histories.empty()) {
          const auto h = std::lower_bound(histories.begin(), histories.end(),
                                          std::pair<std::uint64_t, double>{key, -INFINITY});
          if (h != histories.end() && h->first == key) bf.state[k] = h->second;
        }
      } else if (fgrid) {
        const Vec3 xi{ns.x[0][i], ns.x[1][i], D == 3 ? ns.x[2][i] : 0.0},
            xj{ns.x[0][j], ns.x[1][j], D == 3 ? ns.x[2][j] : 0.0};
        const Vec3 mid = scale(add(xi, xj), 0.5);
        const double r = 0.5 * norm(sub(xj, xi)) + reach;
        fgrid->for_each_within(mid, r, [&](std::uint32_t f, double) {
          if (!broken && mem.facets[f].crossed_by(xi, xj)) broken = true;
        });
      }
      if (broken) bf.beta[k] = -bf.beta[k];
    }
  }
  // Copied rows keep their marks and weights: their neighbours neither changed volume nor flags
  // (a changed node puts every row that reaches it into the window).
  mark_unbreakable_bonds(ns, bf, &rebuild);
  for (std::uint32_t i : recorrected) rebuild[i] = 1;
  index_pairs(bf, ns, m.formulation.dual_horizon, m.formulation.state_based(), &rebuild,
              global ? 0.0 : member_reach);
  update_damage_weights(ns, bf, &rebuild);
  std::vector<std::uint32_t> rows;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (rebuild[i]) rows.push_back(static_cast<std::uint32_t>(i));
  if (m.ghost.enabled) m.ghost.pending.insert(m.ghost.pending.end(), rows.begin(), rows.end());
  return rows;
}

}  // namespace periadapt
