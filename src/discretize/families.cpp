#include "discretize/families.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>

#include "core/cell_grid.hpp"

namespace periadapt {

namespace {

struct Entry {
  std::uint32_t j;
  float beta;
  double inv_len;
};

}  // namespace

std::vector<std::uint32_t> active_nodes_near(const NodeSet& nodes,
                                             const std::vector<std::uint32_t>& seeds, double margin) {
  std::vector<std::uint32_t> out;
  if (seeds.empty()) return out;
  const int D = nodes.dim;
  double lo[3], hi[3];
  for (int d = 0; d < D; ++d) {
    lo[d] = INFINITY, hi[d] = -INFINITY;
    for (std::uint32_t i : seeds) lo[d] = std::min(lo[d], nodes.x[d][i]), hi[d] = std::max(hi[d], nodes.x[d][i]);
    lo[d] -= margin, hi[d] += margin;
  }
  // One light pass over coordinates (no cell list, no per-node search).
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!(nodes.flags[i] & kActive)) continue;
    bool in = true;
    for (int d = 0; d < D; ++d) in = in && nodes.x[d][i] >= lo[d] && nodes.x[d][i] <= hi[d];
    if (in) out.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

namespace {

// The neighbor search: a cell list over all nodes with the largest search radius (or, for a
// set of rows, over the nodes near them).
class FamilySearch {
 public:
  FamilySearch(const NodeSet& nodes, const QuadratureSpec& quad)
      : nodes_(nodes), quad_(quad), cell_reach_(largest_cell(nodes)), grid_(nodes.dim,
                                          {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()},
                                          nodes.size(), search_radius(nodes, quad)) {}
  // Only the rows `rows` will be searched: the cell list holds the active nodes that can be in
  // their families (within their largest search radius of their bounding box). Its cells follow
  // the smallest radius: after refinement most rows are fine ones, and cells sized for the coarse
  // radius made each of them test ~4x more candidates than it has neighbours.
  FamilySearch(const NodeSet& nodes, const QuadratureSpec& quad,
               const std::vector<std::uint32_t>& rows)
      : nodes_(nodes), quad_(quad), cell_reach_(largest_cell(nodes)), grid_(nodes.dim,
                                          {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()},
                                          candidates(nodes, quad, rows, cell_reach_),
                                          cell_size(nodes, quad, rows, cell_reach_)) {}

  // Only the given candidates can be neighbours (ids ascending), in cells of `cell`.
  FamilySearch(const NodeSet& nodes, const QuadratureSpec& quad,
               const std::vector<std::uint32_t>& candidates, double cell)
      : nodes_(nodes), quad_(quad), cell_reach_(largest_cell(nodes)), grid_(nodes.dim,
                                          {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()},
                                          candidates, cell) {}

  // Calls visit(j, 1/xi, beta) for every family member of node i, in a fixed order.
  template <class Visit>
  void visit(std::size_t i, Visit&& visit) const {
    const NodeSet& nodes = nodes_;
    const std::array<double, 3> p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
    const double delta = nodes.horizon[i];
    // A cell reaches into the horizon when its node is within half its own diagonal of it:
    // next to a coarser level that is the coarse cells' reach, not the source's.
    const double radius = quadrature_search_radius(quad_.rule, nodes.dim, delta, cell_reach_);
    // Nodes exactly on the horizon (m integer) are included whatever the rounding.
    grid_.for_each_within(p, radius * (1 + 1e-12), [&](std::uint32_t j, double d2) {
      if (j == i || !(nodes.flags[j] & kActive)) return;
      const double xi = std::sqrt(d2);
      double b;
      if (quad_.rule == Quadrature::Subcell || quad_.rule == Quadrature::IpaHybrid) {
        const std::array<double, 3> off{nodes.x[0][j] - p[0], nodes.x[1][j] - p[1],
                                        nodes.x[2][j] - p[2]};
        b = subcell_fraction(nodes.dim, off, delta, nodes.spacing[j], quad_.lattice_rotation);
      } else {
        b = partial_volume_factor(quad_.rule, std::min(xi, delta), delta, nodes.spacing[j]);
      }
      if (b > 0) visit(j, 1.0 / xi, static_cast<float>(b));
    });
  }

  std::uint64_t count(std::size_t i) const {
    std::uint64_t c = 0;
    visit(i, [&](std::uint32_t, double, float) { ++c; });
    return c;
  }

  // Row i into `out`, sorted by neighbour id (independent of the cell layout, friendlier to the
  // caches); appended after what `out` holds when `append`.
  void collect(std::size_t i, std::vector<Entry>& out, bool append = false) const {
    if (!append) out.clear();
    const auto first = static_cast<long>(out.size());
    visit(i, [&](std::uint32_t j, double il, float b) { out.push_back({j, b, il}); });
    std::sort(out.begin() + first, out.end(), [](const Entry& a, const Entry& b) { return a.j < b.j; });
  }

  // Writes row i at position `at` of the bond arrays.
  void write(std::size_t i, std::uint64_t at, BondFamilies& fam, std::vector<Entry>& scratch) const {
    collect(i, scratch);
    store(scratch, at, fam);
  }

  static void store(const std::vector<Entry>& row, std::uint64_t at, BondFamilies& fam) {
    for (const Entry& e : row) {
      fam.neighbor[at] = e.j;
      fam.inv_length[at] = e.inv_len;
      fam.beta[at] = e.beta;
      if (fam.keeps_state) fam.state[at] = 0.0;  // rebuilt rows get their histories by pair
      ++at;
    }
  }

  // The largest search radius of the rows.
  static double search_radius(const NodeSet& nodes, const QuadratureSpec& quad,
                              const std::vector<std::uint32_t>& rows) {
    return search_radius(nodes, quad, rows, largest_cell(nodes));
  }

 private:
  // The largest spacing of an active node: the farthest any cell reaches beyond its node.
  static double largest_cell(const NodeSet& nodes) {
    double dx = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes.flags[i] & kActive) dx = std::max(dx, nodes.spacing[i]);
    return dx;
  }
  // `dx`: largest_cell(nodes), found once per search.
  static double search_radius(const NodeSet& nodes, const QuadratureSpec& quad,
                              const std::vector<std::uint32_t>& rows, double dx) {
    double h = 0;
    for (std::uint32_t i : rows) h = std::max(h, nodes.horizon[i]);
    const double r = quadrature_search_radius(quad.rule, nodes.dim, h, dx);
    return std::max(r * (1 + 1e-9), 1e-300);
  }
  static double search_radius(const NodeSet& nodes, const QuadratureSpec& quad) {
    double hmax = 0, dxmax = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      hmax = std::max(hmax, nodes.horizon[i]);
      dxmax = std::max(dxmax, nodes.spacing[i]);
    }
    return std::max(quadrature_search_radius(quad.rule, nodes.dim, hmax, dxmax), 1e-300);
  }
  // The smallest search radius of the rows, but at least a quarter of the largest (a query then
  // spans at most 9 cells per axis).
  static double cell_size(const NodeSet& nodes, const QuadratureSpec& quad,
                          const std::vector<std::uint32_t>& rows, double dx) {
    double r = INFINITY;
    for (std::uint32_t i : rows)
      r = std::min(r, quadrature_search_radius(quad.rule, nodes.dim, nodes.horizon[i], dx));
    return std::max(r, 0.25 * search_radius(nodes, quad, rows, dx));
  }
  static std::vector<std::uint32_t> candidates(const NodeSet& nodes, const QuadratureSpec& quad,
                                               const std::vector<std::uint32_t>& rows, double dx) {
    return active_nodes_near(nodes, rows, search_radius(nodes, quad, rows, dx));
  }
  const NodeSet& nodes_;
  const QuadratureSpec& quad_;
  double cell_reach_;
  CellGrid grid_;
};

// Bond arrays of at least `total` entries; growth leaves `headroom` (a fraction of `total`) so
// that a run of refinement events reallocates only now and then: events append their rebuilt
// rows every few steps, and a reallocation copies every bond (with 1/16 it happened every other
// event).
void grow_bond_arrays(BondFamilies& fam, std::size_t total,
                      double headroom = kRefinementBondHeadroom) {
  const auto spare = static_cast<std::size_t>(headroom * static_cast<double>(total));
  auto fit = [total, spare](auto& v) {
    if (v.capacity() < total) v.reserve(total + spare);
    v.resize(total);
  };
  fit(fam.neighbor);
  fit(fam.inv_length);
  fit(fam.beta);
  if (fam.keeps_state) fit(fam.state);
}

}  // namespace

std::vector<std::vector<QuadratureEntry>> quadrature_factors(
    const NodeSet& nodes, const QuadratureSpec& quad, const std::vector<std::uint32_t>& rows) {
  std::vector<std::vector<QuadratureEntry>> out(rows.size());
  if (rows.empty()) return out;
  const FamilySearch search(nodes, quad, rows);
#pragma omp parallel
  {
    std::vector<Entry> row;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (!(nodes.flags[rows[r]] & kActive)) continue;
      search.collect(rows[r], row);
      out[r].reserve(row.size());
      for (const Entry& e : row) out[r].push_back({e.j, e.beta, e.inv_len});
    }
  }
  return out;
}

std::vector<std::uint32_t> nodes_within(const NodeSet& nodes, const std::vector<std::uint32_t>& seeds,
                                        double radius) {
  std::vector<char> in(nodes.size(), 0);
  for (std::uint32_t i : seeds) in[i] = 1;
  if (!seeds.empty()) {
    const double r = std::max(radius, 1e-300);
    const CellGrid grid(nodes.dim, {nodes.x[0].data(), nodes.x[1].data(), nodes.x[2].data()},
                        active_nodes_near(nodes, seeds, r), r);
    for (std::uint32_t c : seeds)
      grid.for_each_within({nodes.x[0][c], nodes.x[1][c], nodes.x[2][c]}, r,
                           [&](std::uint32_t j, double) { in[j] = 1; });
  }
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (in[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

namespace {

bool searched(const NodeSet& nodes, const std::vector<char>* rows, std::size_t i) {
  return (nodes.flags[i] & kActive) && (!rows || (*rows)[i]);
}

// Row begins from the count pass over the searched rows.
std::vector<std::uint64_t> counted_offsets(const NodeSet& nodes, const FamilySearch& search,
                                           const std::vector<char>* rows) {
  const std::size_t n = nodes.size();
  std::vector<std::uint64_t> offsets(n + 1, 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i)
    if (searched(nodes, rows, i)) offsets[i + 1] = search.count(i);
  for (std::size_t i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  return offsets;
}

}  // namespace

BondFamilies build_families(const NodeSet& nodes, const QuadratureSpec& quad, double headroom,
                            const std::vector<char>* rows) {
  const std::size_t n = nodes.size();
  BondFamilies fam;
  fam.offsets.assign(n + 1, 0);
  if (n == 0) return fam;  // no rows: ends empty, live 0
  const FamilySearch search(nodes, quad);
  // Two passes (count, then fill in place) so that the only bond-sized memory ever allocated is
  // the final CSR arrays: no per-thread buffers, no copy.
  fam.offsets = counted_offsets(nodes, search, rows);
  grow_bond_arrays(fam, fam.offsets[n], headroom);
#pragma omp parallel
  {
    std::vector<Entry> scratch;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i)
      if (searched(nodes, rows, i)) search.write(i, fam.offsets[i], fam, scratch);
  }
  fam.close_contiguous();
  return fam;
}

void grow_by_families(const NodeSet& nodes, const QuadratureSpec& quad, std::vector<char>& rows,
                      int layers, const BondFamilies* bonds, const std::vector<char>* current) {
  if (nodes.size() == 0 || layers < 1) return;
  // A row whose bond list is current has the search's members as its neighbours: those are read
  // from the list, and the cell list is built only if some row has none.
  auto listed = [&](std::uint32_t i) {
    return bonds && current && i < current->size() && (*current)[i] && i < bonds->num_nodes();
  };
  std::optional<FamilySearch> search;
  std::vector<std::uint32_t> frontier;
  // An inactive row (a refined parent) has no family.
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i] && (nodes.flags[i] & kActive)) frontier.push_back(static_cast<std::uint32_t>(i));
  for (int layer = 0; layer < layers && !frontier.empty(); ++layer) {
    // Only the rows the last layer added have members not marked yet.
    std::vector<char> grown(rows);
    auto mark = [&](std::uint32_t j) {
      std::atomic_ref<char>(grown[j]).store(1, std::memory_order_relaxed);
    };
    bool unlisted = false;
    for (std::uint32_t i : frontier) unlisted = unlisted || !listed(i);
    if (unlisted && !search) search.emplace(nodes, quad);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t q = 0; q < frontier.size(); ++q) {
      const std::uint32_t i = frontier[q];
      if (listed(i)) {
        for (std::uint64_t k = bonds->begin(i); k < bonds->end(i); ++k) mark(bonds->neighbor[k]);
      } else {
        search->visit(i, [&](std::uint32_t j, double, float) { mark(j); });
      }
    }
    frontier.clear();
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (grown[i] && !rows[i]) frontier.push_back(static_cast<std::uint32_t>(i));
    rows = std::move(grown);
  }
}

std::vector<std::uint64_t> family_offsets(const NodeSet& nodes, const QuadratureSpec& quad,
                                          const std::vector<char>* rows) {
  if (nodes.size() == 0) return {0};
  return counted_offsets(nodes, FamilySearch(nodes, quad), rows);
}

void rebuild_rows(BondFamilies& fam, const NodeSet& nodes, const QuadratureSpec& quad,
                  const std::vector<char>& rows, const std::vector<char>* patch) {
  const std::size_t n = nodes.size(), n_old = fam.num_nodes();
  const std::uint64_t tail = fam.neighbor.size();
  if (fam.ends.empty()) fam.ends.assign(fam.offsets.begin() + 1, fam.offsets.end());
  // New nodes start with empty rows.
  fam.offsets.resize(n + 1, tail);
  fam.ends.resize(n, tail);
  for (std::size_t i = n_old; i < n; ++i) fam.offsets[i] = fam.ends[i] = tail;
  fam.t_offsets.clear();
  fam.t_owner.clear();
  fam.t_bond.clear();
  // The far-end factors stay: index_pairs redoes the rows this changes and keeps the others'
  // (stored by place in their row, which a move keeps).
  std::vector<std::uint32_t> list;
  for (std::size_t i = 0; i < n; ++i)
    if (i < rows.size() && rows[i]) list.push_back(static_cast<std::uint32_t>(i));
  if (list.empty()) return;
  // Rows to search in full, and rows to patch (their old entries, then the appended nodes).
  auto patched_row = [&](std::uint32_t i) {
    return patch && i < n_old && i < patch->size() && (*patch)[i];
  };
  std::vector<std::uint32_t> full, patched, fresh;
  for (std::uint32_t i : list) (patched_row(i) ? patched : full).push_back(i);
  if (!patched.empty())
    for (std::size_t i = n_old; i < n; ++i)
      if (nodes.flags[i] & kActive) fresh.push_back(static_cast<std::uint32_t>(i));
  const FamilySearch search = full.empty() ? FamilySearch(nodes, quad, std::vector<std::uint32_t>{}, 1.0)
                                            : FamilySearch(nodes, quad, full);
  const FamilySearch newcomers(nodes, quad, fresh,
                              patched.empty() ? 1.0 : FamilySearch::search_radius(nodes, quad, patched));
  // One search per row, into a buffer per row: a window's rows are few, so unlike the full
  // build (which counts first and allocates nothing but the final arrays) the search runs once.
  std::vector<std::vector<Entry>> found(list.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t r = 0; r < list.size(); ++r) {
    const std::uint32_t i = list[r];
    if (!(nodes.flags[i] & kActive)) continue;
    if (!patched_row(i)) {
      search.collect(i, found[r]);
      continue;
    }
    // Old neighbours still active, in their (ascending) order and with their bond states;
    // appended nodes have larger ids, so the row stays sorted.
    std::vector<Entry>& out = found[r];
    for (std::uint64_t k = fam.offsets[i]; k < fam.ends[i]; ++k)
      if (nodes.flags[fam.neighbor[k]] & kActive)
        out.push_back({fam.neighbor[k], fam.beta[k], fam.inv_length[k]});
    if (!fresh.empty()) newcomers.collect(i, out, true);
  }
  std::uint64_t appended = 0, dropped = 0;
  for (std::size_t r = 0; r < list.size(); ++r) {
    appended += found[r].size();
    dropped += fam.ends[list[r]] - fam.offsets[list[r]];
  }
  const std::uint64_t live = fam.live - dropped + appended, total = tail + appended;
  // Compact when appending would reallocate (a reallocation copies every bond, slack included,
  // and a compaction would follow soon) or would leave slack above a quarter of the live bonds:
  // one copy, rows back in node order, the rebuilt ones taken from the search.
  if (total > fam.neighbor.capacity() || total - live > live / 4) {
    BondFamilies c;
    c.keeps_state = fam.keeps_state;
    c.offsets.assign(n + 1, 0);
    std::vector<std::uint32_t> slot(n, UINT32_MAX);  // row -> index into `found`
    for (std::size_t r = 0; r < list.size(); ++r) slot[list[r]] = static_cast<std::uint32_t>(r);
    for (std::size_t i = 0; i < n; ++i)
      c.offsets[i + 1] = c.offsets[i] + (slot[i] != UINT32_MAX ? found[slot[i]].size()
                                                                : fam.ends[i] - fam.offsets[i]);
    // With the growth headroom, so that the next events append without copying.
    grow_bond_arrays(c, c.offsets[n]);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      if (slot[i] != UINT32_MAX) {
        FamilySearch::store(found[slot[i]], c.offsets[i], c);
        continue;
      }
      const auto b = static_cast<long>(fam.offsets[i]), e = static_cast<long>(fam.ends[i]);
      const auto o = static_cast<long>(c.offsets[i]);
      std::copy(fam.neighbor.begin() + b, fam.neighbor.begin() + e, c.neighbor.begin() + o);
      std::copy(fam.inv_length.begin() + b, fam.inv_length.begin() + e, c.inv_length.begin() + o);
      std::copy(fam.beta.begin() + b, fam.beta.begin() + e, c.beta.begin() + o);
      if (fam.keeps_state)
        std::copy(fam.state.begin() + b, fam.state.begin() + e, c.state.begin() + o);
    }
    c.close_contiguous();
    c.reverse_at = std::move(fam.reverse_at);
    c.reverse_beta = std::move(fam.reverse_beta);
    fam = std::move(c);
    return;
  }
  // Rebuilt rows go after everything else, in node order; their old entries become slack.
  std::uint64_t at = tail;
  for (std::size_t r = 0; r < list.size(); ++r) {
    const std::size_t i = list[r];
    fam.offsets[i] = at;
    fam.ends[i] = at + found[r].size();
    at += found[r].size();
  }
  fam.live = live;
  grow_bond_arrays(fam, at);
  fam.offsets[n] = at;
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t r = 0; r < list.size(); ++r)
    FamilySearch::store(found[r], fam.offsets[list[r]], fam);
}

void build_transpose(BondFamilies& bf) {
  const std::size_t n = bf.num_nodes();
  bf.t_offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) ++bf.t_offsets[bf.neighbor[k] + 1];
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

namespace {

// Row i's far-end factors (each bond's factor in its far end's row, found by bisection there:
// rows are sorted by neighbour id), or none where they all equal its own. Only rows with a far
// end of another horizon or cell size are searched: the rules and corrections are symmetric
// between equal ones.
std::vector<float> far_factors(const BondFamilies& bf, const NodeSet& ns, std::size_t i) {
  bool candidate = false;
  for (std::uint64_t k = bf.begin(i); k < bf.end(i) && !candidate; ++k) {
    const std::uint32_t j = bf.neighbor[k];
    candidate = ns.horizon[j] != ns.horizon[i] || ns.spacing[j] != ns.spacing[i];
  }
  if (!candidate) return {};
  std::vector<float> f(bf.end(i) - bf.begin(i), 0.0f);
  bool mixed = false;
  for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
    const std::uint32_t j = bf.neighbor[k];
    const auto first = bf.neighbor.begin() + static_cast<long>(bf.begin(j));
    const auto last = bf.neighbor.begin() + static_cast<long>(bf.end(j));
    const auto at = std::lower_bound(first, last, static_cast<std::uint32_t>(i));
    float& v = f[k - bf.begin(i)];
    if (at != last && *at == i) v = std::abs(bf.beta[static_cast<std::size_t>(at - bf.neighbor.begin())]);
    mixed = mixed || v != std::abs(bf.beta[k]);
  }
  if (!mixed) f.clear();
  return f;
}

// reverse_beta holding exactly the rows' factors that reverse_at points at, in node order.
void pack_reverse(BondFamilies& bf) {
  std::vector<float> packed;
  for (std::size_t i = 0; i < bf.reverse_at.size(); ++i) {
    if (bf.reverse_at[i] == BondFamilies::kNoReverse) continue;
    const auto from = bf.reverse_beta.begin() + static_cast<long>(bf.reverse_at[i]);
    bf.reverse_at[i] = packed.size();
    packed.insert(packed.end(), from, from + static_cast<long>(bf.end(i) - bf.begin(i)));
  }
  bf.reverse_beta = std::move(packed);
}

}  // namespace

void build_reverse(BondFamilies& bf, const NodeSet& ns, const std::vector<char>* redo) {
  const std::size_t n = bf.num_nodes();
  // Rows to make: all, or those asked for and the rows new since the last build. The others
  // keep the factors they had, where they lie.
  std::vector<std::uint32_t> rows;
  const bool all = !redo || bf.reverse_at.empty();
  for (std::size_t i = 0; i < n; ++i)
    if (all || i >= bf.reverse_at.size() || i >= redo->size() || (*redo)[i])
      rows.push_back(static_cast<std::uint32_t>(i));
  std::vector<std::vector<float>> far(rows.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t r = 0; r < rows.size(); ++r) far[r] = far_factors(bf, ns, rows[r]);
  if (all) {
    bf.reverse_at.assign(n, BondFamilies::kNoReverse);
    bf.reverse_beta.clear();
  } else {
    bf.reverse_at.resize(n, BondFamilies::kNoReverse);
  }
  // Remade rows go after the others; their old entries become slack.
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (far[r].empty()) {
      bf.reverse_at[rows[r]] = BondFamilies::kNoReverse;
      continue;
    }
    bf.reverse_at[rows[r]] = bf.reverse_beta.size();
    bf.reverse_beta.insert(bf.reverse_beta.end(), far[r].begin(), far[r].end());
  }
  std::uint64_t live = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (bf.reverse_at[i] != BondFamilies::kNoReverse) live += bf.end(i) - bf.begin(i);
  if (bf.reverse_beta.size() > live + live / 4) pack_reverse(bf);
}

void index_pairs(BondFamilies& bf, const NodeSet& ns, bool dual_horizon, bool state_based,
                 const std::vector<char>* changed, double member_reach) {
  if (dual_horizon) {
    bf.reverse_at.clear();
    bf.reverse_beta.clear();
    build_transpose(bf);
    return;
  }
  double lo = INFINITY, hi = -INFINITY;
  if (state_based)
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) {
        lo = std::min(lo, ns.horizon[i]);
        hi = std::max(hi, ns.horizon[i]);
      }
  if (!(lo < hi)) {
    bf.reverse_at.clear();
    bf.reverse_beta.clear();
    return;
  }
  if (!changed || bf.reverse_at.empty()) {
    build_reverse(bf, ns);
    return;
  }
  // A row's far-end factors change with its own row and with its far ends' rows: the rows to
  // look at are all, or those within a member's reach of a changed one.
  const std::size_t n = bf.num_nodes();
  std::vector<std::uint32_t> look;
  if (member_reach > 0) {
    std::vector<std::uint32_t> seeds;
    for (std::size_t i = 0; i < n; ++i)
      if (i >= changed->size() || (*changed)[i]) seeds.push_back(static_cast<std::uint32_t>(i));
    look = nodes_within(ns, seeds, member_reach);
  } else {
    look.resize(n);
    for (std::size_t i = 0; i < n; ++i) look[i] = static_cast<std::uint32_t>(i);
  }
  std::vector<char> redo(n, 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t q = 0; q < look.size(); ++q) {
    const std::uint32_t i = look[q];
    if (i >= n) continue;
    bool r = i >= changed->size() || (*changed)[i];
    for (std::uint64_t k = bf.begin(i); k < bf.end(i) && !r; ++k)
      r = bf.neighbor[k] < changed->size() ? (*changed)[bf.neighbor[k]] != 0 : true;
    redo[i] = r;
  }
  build_reverse(bf, ns, &redo);
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
