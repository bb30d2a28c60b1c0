#include "solver/ghost_correction.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "discretize/families.hpp"
#include "discretize/interface_quadrature.hpp"
#include "material/force_model.hpp"

namespace periadapt {

namespace {

// Strain component c as the index pair (p, q): xx (1D); xx, yy, xy (2D); xx, yy, zz, yz, xz, xy.
void component(int dim, int c, int& p, int& q) {
  static const int two[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  static const int three[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  const int(*t)[2] = dim == 3 ? three : two;
  p = t[c][0];
  q = t[c][1];
}

int components_of(int dim) { return dim == 1 ? 1 : dim == 2 ? 3 : 6; }

}  // namespace

void update_ghost_table(Model& m) {
  GhostTable& g = m.ghost;
  if (!g.enabled || (!g.rebuild_all && g.pending.empty())) return;
  NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  const std::size_t n = ns.size();
  const int D = ns.dim;
  const bool state = m.formulation.state_based();
  g.components = components_of(D);
  const int C = g.components;
  // Nodes plus the far ends of their rows (no repeats; `in` marks what is listed).
  std::vector<char> in(n, 0);
  auto grow = [&](std::vector<std::uint32_t>& set) {
    const std::size_t end = set.size();
    for (std::size_t q = 0; q < end; ++q)
      for (std::uint64_t k = bf.begin(set[q]); k < bf.end(set[q]); ++k)
        if (!in[bf.neighbor[k]]) in[bf.neighbor[k]] = 1, set.push_back(bf.neighbor[k]);
  };
  // The rows to (re)compute: a row's force under a uniform strain depends on its own family
  // and, state-based, on the families of the nodes it reaches (their dilatations): every row
  // within the largest horizon of a changed one.
  std::vector<std::uint32_t> redo;
  if (g.rebuild_all) {
    for (std::size_t i = 0; i < n; ++i)
      if (ns.flags[i] & kActive) redo.push_back(static_cast<std::uint32_t>(i));
  } else if (state) {
    double hmax = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (ns.flags[i] & kActive) hmax = std::max(hmax, ns.horizon[i]);
    std::vector<std::uint32_t> seeds;
    for (std::uint32_t i : g.pending)
      if (i < n && (ns.flags[i] & kActive)) seeds.push_back(i);
    if (!seeds.empty()) redo = active_nodes_near(ns, seeds, hmax * (1 + 1e-9));
  } else {
    for (std::uint32_t i : g.pending)
      if (i < n && (ns.flags[i] & kActive) && !in[i]) in[i] = 1, redo.push_back(i);
    for (std::uint32_t i : redo) in[i] = 0;
  }
  g.rebuild_all = false;
  g.pending.clear();
  std::vector<char> redone(n, 0);
  for (std::uint32_t i : redo) redone[i] = 1;
  // Drop the rows being redone (and inactive ones) from the table.
  std::vector<std::uint32_t> keep_rows;
  std::vector<double> keep_G, keep_K;
  for (std::size_t r = 0; r < g.rows.size(); ++r) {
    const std::uint32_t i = g.rows[r];
    if (i >= n || redone[i] || !(ns.flags[i] & kActive)) continue;
    keep_rows.push_back(i);
    keep_G.insert(keep_G.end(), g.G.begin() + r * C * 3, g.G.begin() + (r + 1) * C * 3);
    keep_K.insert(keep_K.end(), g.Kinv.begin() + r * 9, g.Kinv.begin() + (r + 1) * 9);
  }
  // Every redone row's response is measured (a table that depends only on each row's own
  // inputs is the same whether built whole or event by event); only rows above round-off whose
  // balls, and state-based their neighbours' balls, are covered by cells are kept.
  const std::vector<std::uint32_t>& rows = redo;
  std::vector<double> G(rows.size() * C * 3, 0.0);
  if (!rows.empty()) {
    // What the rows' pass reads: the rows' dilatation rows (state-based) and their far ends.
    std::vector<std::uint32_t> dil = rows;
    for (std::uint32_t i : dil) in[i] = 1;
    if (state) grow(dil);
    std::vector<std::uint32_t> moved = dil;
    grow(moved);
    for (std::uint32_t i : moved) in[i] = 0;
    std::vector<double> cur_saved(moved.size() * 3), f_saved(rows.size() * 3);
    // The passes below overwrite the LPS scratch, which the energy densities read.
    const LpsScratch scratch_saved = state ? m.lps_scratch : LpsScratch{};
    for (std::size_t q = 0; q < moved.size(); ++q)
      for (int d = 0; d < 3; ++d) cur_saved[3 * q + d] = ns.cur[4 * std::size_t{moved[q]} + d];
    for (std::size_t q = 0; q < rows.size(); ++q)
      for (int d = 0; d < 3; ++d) f_saved[3 * q + d] = ns.f[d][rows[q]];
    // The rows' forces under +-h of each unit strain component, from the material alone:
    // G = (F(h) - F(-h)) / 2h. Central, so that the force's second-order part (the same for a
    // strain and its mirror image, while the first-order part changes sign with the shear) drops
    // out: one-sided, it left mirror images' responses 1e-6 - 1e-4 apart; a thermal strain's
    // force at zero strain drops out too.
    constexpr double h = 1e-6;
    auto pass_at = [&](int c, double amount, double* out, double scale) {
      int p = 0, q = 0;
      component(D, c, p, q);
      for (std::uint32_t i : moved) {
        double y[3] = {ns.x[0][i], ns.x[1][i], ns.x[2][i]};
        y[p] += amount * ns.x[q][i];
        if (p != q) y[q] += amount * ns.x[p][i];
        for (int d = 0; d < 3; ++d) ns.cur[4 * std::size_t{i} + d] = y[d];
      }
      ForcePass pass;
      pass.rows = &rows;
      if (state) pass.dilatation_rows = &dil;
      material_forces(ns, m.bonds, material_context(m), pass);
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (int d = 0; d < D; ++d) out[r * C * 3 + d] += scale * ns.f[d][rows[r]];
    };
    for (int c = 0; c < C; ++c) {
      pass_at(c, h, G.data() + c * 3, 0.5 / h);
      pass_at(c, -h, G.data() + c * 3, -0.5 / h);
    }
    for (std::size_t q = 0; q < moved.size(); ++q)
      for (int d = 0; d < 3; ++d) ns.cur[4 * std::size_t{moved[q]} + d] = cur_saved[3 * q + d];
    for (std::size_t q = 0; q < rows.size(); ++q)
      for (int d = 0; d < 3; ++d) ns.f[d][rows[q]] = f_saved[3 * q + d];
    if (state) m.lps_scratch = scratch_saved;
  }
  // Above round-off: E / delta per unit strain is the scale of a strain jump across a horizon.
  const double E = m.material.E;
  std::vector<std::uint32_t> strong;
  std::vector<char> is_strong(n, 0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    double mx = 0;
    for (int c = 0; c < C * 3; ++c) mx = std::max(mx, std::abs(G[r * C * 3 + c]));
    if (mx > 1e-6 * E / ns.horizon[rows[r]]) strong.push_back(rows[r]), is_strong[rows[r]] = 1;
  }
  std::vector<std::uint32_t> check = strong;
  for (std::uint32_t i : check) in[i] = 1;
  if (state) grow(check);
  for (std::uint32_t i : check) in[i] = 0;
  g.covered.resize(n, 0);
  g.covered_at.resize(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::uint32_t> unknown;
  for (std::uint32_t i : check)
    if (!(g.covered_at[i] == ns.horizon[i])) unknown.push_back(i);
  const std::vector<char> cov = rows_with_covered_ball(ns, unknown);
  for (std::size_t q = 0; q < unknown.size(); ++q) {
    g.covered[unknown[q]] = cov[q];
    g.covered_at[unknown[q]] = ns.horizon[unknown[q]];
  }
  const std::vector<char>& covered = g.covered;
  // The table in node order, so that it is the same however it was built.
  struct Entry {
    std::uint32_t node;
    bool fresh;     // computed now (else kept from the table)
    std::size_t r;  // its index in rows (fresh) or keep_rows
  };
  std::vector<Entry> order;
  for (std::size_t r = 0; r < keep_rows.size(); ++r) order.push_back({keep_rows[r], false, r});
  std::vector<double> new_K(rows.size() * 9, 0.0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::uint32_t i = rows[r];
    bool good = is_strong[i] && covered[i];
    if (state)
      for (std::uint64_t k = bf.begin(i); k < bf.end(i) && good; ++k) good = covered[bf.neighbor[k]];
    if (!good) continue;
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      const Eigen::Vector3d xi(ns.x[0][j] - ns.x[0][i], ns.x[1][j] - ns.x[1][i],
                               ns.x[2][j] - ns.x[2][i]);
      K += xi * xi.transpose();
    }
    for (int d = D; d < 3; ++d) K(d, d) = 1.0;
    const Eigen::Matrix3d Ki = K.inverse();
    if (!Ki.allFinite()) continue;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) new_K[r * 9 + 3 * a + b] = Ki(a, b);
    order.push_back({i, true, r});
  }
  std::sort(order.begin(), order.end(), [](const Entry& a, const Entry& b) { return a.node < b.node; });
  g.rows.clear();
  g.G.clear();
  g.Kinv.clear();
  for (const Entry& e : order) {
    const std::vector<double>& Gs = e.fresh ? G : keep_G;
    const std::vector<double>& Ks = e.fresh ? new_K : keep_K;
    const std::size_t r = e.r;
    g.rows.push_back(e.node);
    g.G.insert(g.G.end(), Gs.begin() + r * C * 3, Gs.begin() + (r + 1) * C * 3);
    g.Kinv.insert(g.Kinv.end(), Ks.begin() + r * 9, Ks.begin() + (r + 1) * 9);
  }
  g.slot.assign(n, UINT32_MAX);
  for (std::size_t r = 0; r < g.rows.size(); ++r) g.slot[g.rows[r]] = static_cast<std::uint32_t>(r);
}

namespace {

// The correction of the table's rows (all, or those of `rows`): D a template argument so that
// the bond loops unroll and vectorize.
template <int D>
void correct_rows(Model& m, const std::vector<std::uint32_t>* rows) {
  GhostTable& g = m.ghost;
  NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  const int C = g.components;
  const double* y = ns.cur.data();
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* X[3] = {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()};
  const bool state = m.formulation.state_based();
  auto one = [&](std::size_t r) {
    const std::uint32_t i = g.rows[r];
    if (!(ns.flags[i] & kActive) || ns.broken_weight[i] > 0) return;
    // Displacement gradient H = (sum (u_j - u_i) (x) xi) K^-1 over the row's bonds, from the
    // positions the pass used (core/visible_gradient reads u, which a multi-rate slow row's drift
    // has left behind, and forms its moment matrix again each time). A state-based row whose
    // neighbours have a broken bond is cut (their dilatations see the crack): no uniform strain.
    double A[D][D] = {};
    double yi[D], xi_i[D];
    for (int a = 0; a < D; ++a) xi_i[a] = X[a][i], yi[a] = y[4 * std::size_t{i} + a];
    bool cut = false;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = nbr[k];
      if (state) cut |= ns.broken_weight[j] > 0;
      double xi[D], du[D];
      for (int a = 0; a < D; ++a) {
        xi[a] = X[a][j] - xi_i[a];
        du[a] = (y[4 * std::size_t{j} + a] - yi[a]) - xi[a];
      }
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b) A[a][b] += du[a] * xi[b];
    }
    if (cut) return;
    const double* Ki = &g.Kinv[r * 9];
    double H[D][D] = {};
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        for (int c = 0; c < D; ++c) H[a][b] += A[a][c] * Ki[3 * c + b];
    const double* Gi = &g.G[r * C * 3];
    for (int c = 0; c < C; ++c) {
      int p, q;
      component(D, c, p, q);
      const double e = 0.5 * (H[p][q] + H[q][p]);
      for (int d = 0; d < D; ++d) ns.f[d][i] -= Gi[c * 3 + d] * e;
    }
  };
  if (rows) {
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t q = 0; q < rows->size(); ++q) {
      const std::uint32_t i = (*rows)[q];
      if (i < g.slot.size() && g.slot[i] != UINT32_MAX) one(g.slot[i]);
    }
  } else {
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t r = 0; r < g.rows.size(); ++r) one(r);
  }
}

}  // namespace

void apply_ghost_correction(Model& m, const std::vector<std::uint32_t>* rows) {
  GhostTable& g = m.ghost;
  if (!g.enabled) return;
  update_ghost_table(m);
  if (g.rows.empty()) return;
  switch (m.nodes.dim) {
    case 1: return correct_rows<1>(m, rows);
    case 2: return correct_rows<2>(m, rows);
    default: return correct_rows<3>(m, rows);
  }
}

}  // namespace periadapt
