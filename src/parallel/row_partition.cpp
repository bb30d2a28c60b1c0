#include "parallel/row_partition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "parallel/ghost_layer.hpp"
#include "parallel/mpi_env.hpp"

#ifdef PERIADAPT_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>
#endif

namespace periadapt {

namespace {

// A row's bonds evaluated per step: its bonds over its multi-rate step in units of dt (a node
// without a known step, e.g. a new one, takes dt).
double row_work(const BondFamilies& bf, const std::vector<std::uint8_t>& rates, std::size_t i) {
  const double rate = i < rates.size() && rates[i] > 1 ? static_cast<double>(rates[i]) : 1.0;
  return static_cast<double>(bf.end(i) - bf.begin(i)) / rate;
}

#ifdef PERIADAPT_HAVE_MPI
// What Zoltan's callbacks read: the nodes this rank hands in. The first split hands in a
// contiguous id range (every rank holds all nodes, so any disjoint split is a valid start); a
// repartition hands in the rank's current rows.
struct ZoltanInput {
  const NodeSet* ns;
  const BondFamilies* bf;
  const std::vector<std::uint8_t>* rates;
  std::vector<std::uint32_t> ids;
};

float row_weight(const NodeSet& ns, const BondFamilies& bf, const std::vector<std::uint8_t>& rates,
                 std::uint32_t i) {
  // Zoltan's weight: the row's work, plus a little for the node itself (an inactive row costs a
  // flag test).
  if (!(ns.flags[i] & kActive)) return 0.01f;
  return static_cast<float>(row_work(bf, rates, i) + 1.0);
}

int num_obj(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<int>(static_cast<ZoltanInput*>(data)->ids.size());
}

void obj_list(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int wdim, float* w,
              int* ierr) {
  const auto& in = *static_cast<ZoltanInput*>(data);
  for (std::size_t k = 0; k < in.ids.size(); ++k) {
    gids[k] = in.ids[k];
    lids[k] = static_cast<ZOLTAN_ID_TYPE>(k);
    if (wdim == 1) w[k] = row_weight(*in.ns, *in.bf, *in.rates, in.ids[k]);
  }
  *ierr = ZOLTAN_OK;
}

int num_geom(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<ZoltanInput*>(data)->ns->dim;
}

// The coordinates go to Zoltan last axis first. RCB cuts across the longest extent and, on a
// tie, across the first coordinate it is given; lattices number the longest axis slowest and, on
// a tie, the higher one (discretize/grid.cpp), so either way the cut runs across the axis
// numbered slowest and each rank's rows lie in one stretch of memory rather than in part of
// every line (the 3D block on 2 ranks: about 12% faster per step).
void geom_multi(void* data, int, int, int n, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR, int dim,
                double* xyz, int* ierr) {
  const auto& in = *static_cast<ZoltanInput*>(data);
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < dim; ++d)
      xyz[k * dim + d] = in.ns->x[static_cast<std::size_t>(dim - 1 - d)][gids[k]];
  *ierr = ZOLTAN_OK;
}

// The rank of every node: a fresh split when `current` is empty, else a repartition that starts
// from `current` (the rank of every node).
std::vector<int> zoltan_owners(const NodeSet& ns, const BondFamilies& bf,
                               const std::vector<std::uint8_t>& rates, PartitionMethod method,
                               const std::vector<int>& current) {
  const std::size_t n = ns.size();
  const int P = mpi::size(), r = mpi::rank();
  ZoltanInput in{&ns, &bf, &rates, {}};
  if (current.empty()) {
    const std::size_t lo = n * static_cast<std::size_t>(r) / static_cast<std::size_t>(P);
    const std::size_t hi = n * static_cast<std::size_t>(r + 1) / static_cast<std::size_t>(P);
    for (std::size_t i = lo; i < hi; ++i) in.ids.push_back(static_cast<std::uint32_t>(i));
  } else {
    for (std::size_t i = 0; i < n; ++i)
      if (current[i] == r) in.ids.push_back(static_cast<std::uint32_t>(i));
  }
  Zoltan_Struct* zz = Zoltan_Create(MPI_COMM_WORLD);
  Zoltan_Set_Param(zz, "DEBUG_LEVEL", "0");
  Zoltan_Set_Param(zz, "LB_METHOD", method == PartitionMethod::Rcb ? "RCB" : "HSFC");
  Zoltan_Set_Param(zz, "LB_APPROACH", current.empty() ? "PARTITION" : "REPARTITION");
  Zoltan_Set_Param(zz, "NUM_GID_ENTRIES", "1");
  Zoltan_Set_Param(zz, "NUM_LID_ENTRIES", "1");
  Zoltan_Set_Param(zz, "OBJ_WEIGHT_DIM", "1");
  Zoltan_Set_Param(zz, "RETURN_LISTS", "EXPORT");
  Zoltan_Set_Param(zz, "IMBALANCE_TOL", "1.02");
  Zoltan_Set_Num_Obj_Fn(zz, num_obj, &in);
  Zoltan_Set_Obj_List_Fn(zz, obj_list, &in);
  Zoltan_Set_Num_Geom_Fn(zz, num_geom, &in);
  Zoltan_Set_Geom_Multi_Fn(zz, geom_multi, &in);
  int changes = 0, ngid = 0, nlid = 0, nimp = 0, nexp = 0;
  ZOLTAN_ID_PTR imp_g = nullptr, imp_l = nullptr, exp_g = nullptr, exp_l = nullptr;
  int *imp_p = nullptr, *imp_to = nullptr, *exp_p = nullptr, *exp_to = nullptr;
  const int rc = Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &imp_g, &imp_l, &imp_p,
                                     &imp_to, &nexp, &exp_g, &exp_l, &exp_p, &exp_to);
  if (rc != ZOLTAN_OK) {
    Zoltan_Destroy(&zz);
    throw std::runtime_error("Zoltan could not partition the nodes (error " + std::to_string(rc) + ")");
  }
  // Objects not exported stay on this rank; every rank then learns every node's new rank.
  std::vector<int> mine(in.ids.size(), r);
  for (int k = 0; k < nexp; ++k) mine[exp_l[k]] = exp_p[k];
  Zoltan_LB_Free_Part(&imp_g, &imp_l, &imp_p, &imp_to);
  Zoltan_LB_Free_Part(&exp_g, &exp_l, &exp_p, &exp_to);
  Zoltan_Destroy(&zz);
  std::vector<std::uint32_t> pairs;  // (id, rank) of the nodes handed in here
  pairs.reserve(2 * mine.size());
  for (std::size_t k = 0; k < mine.size(); ++k) {
    pairs.push_back(in.ids[k]);
    pairs.push_back(static_cast<std::uint32_t>(mine[k]));
  }
  const std::vector<std::uint32_t> all = mpi::all_gather(pairs);
  std::vector<int> owner(n, 0);
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    owner[static_cast<std::size_t>(all[k])] = static_cast<int>(all[k + 1]);
  return owner;
}
#endif

}  // namespace

namespace {

// Each rank's work (of its active rows) under `owner`; nodes beyond `owner` or with rank -1 count
// for none.
std::vector<double> rank_work(const NodeSet& ns, const BondFamilies& bf,
                              const std::vector<std::uint8_t>& rates, const std::vector<int>& owner) {
  std::vector<double> work(static_cast<std::size_t>(mpi::size()), 0.0);
  for (std::size_t i = 0; i < std::min(ns.size(), owner.size()); ++i)
    if ((ns.flags[i] & kActive) && owner[i] >= 0)
      work[static_cast<std::size_t>(owner[i])] += row_work(bf, rates, i);
  return work;
}

// The largest rank's work over the mean under `owner`.
double work_imbalance(const NodeSet& ns, const BondFamilies& bf,
                      const std::vector<std::uint8_t>& rates, const std::vector<int>& owner) {
  const std::vector<double> work = rank_work(ns, bf, rates, owner);
  const double mean = std::accumulate(work.begin(), work.end(), 0.0) / static_cast<double>(work.size());
  return mean > 0 ? *std::max_element(work.begin(), work.end()) / mean : 1.0;
}

void adopt_owners(RowPartition& p, std::vector<int> owner) {
  const int me = mpi::rank();
  p.owner = std::move(owner);
  p.owned.clear();
  p.mine.assign(p.owner.size(), 0);
  for (std::size_t i = 0; i < p.owner.size(); ++i) {
    if (p.owner[i] != me) continue;
    p.owned.push_back(static_cast<std::uint32_t>(i));
    p.mine[i] = 1;
  }
  ++p.generation;
  p.all_owned.clear();
  for (int r = 0; r < mpi::size(); ++r)
    for (std::size_t i = 0; i < p.owner.size(); ++i)
      if (p.owner[i] == r) p.all_owned.push_back(static_cast<std::uint32_t>(i));
}

}  // namespace

void refresh_partition(RowPartition& p, const NodeSet& ns, const BondFamilies& bf) {
  if (!p.active || (p.nodes == ns.size() && p.bonds == bf.neighbor.size())) return;
#ifdef PERIADAPT_HAVE_MPI
  std::vector<int> owner;
  if (p.owner.empty()) {
    owner = zoltan_owners(ns, bf, p.rates, p.method, {});
    ++p.partitions;
  } else {
    // Children join their parent's rank (a node without one, the rank with the least work).
    owner = p.owner;
    std::vector<double> load = rank_work(ns, bf, p.rates, owner);
    owner.resize(ns.size(), -1);
    for (std::size_t i = p.owner.size(); i < ns.size(); ++i) {
      const std::int32_t a = ns.parent[i];  // older than i, so it has its rank already
      owner[i] = a >= 0 ? owner[static_cast<std::size_t>(a)]
                        : static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
      if (ns.flags[i] & kActive)
        load[static_cast<std::size_t>(owner[i])] += row_work(bf, p.rates, i);
    }
    if (work_imbalance(ns, bf, p.rates, owner) > 1.0 + p.rebalance_threshold) {
      owner = zoltan_owners(ns, bf, p.rates, p.method, owner);
      ++p.partitions;
    } else {
      ++p.extensions;
    }
  }
  adopt_owners(p, std::move(owner));
  p.imbalance = work_imbalance(ns, bf, p.rates, p.owner);
  p.nodes = ns.size();
  p.bonds = bf.neighbor.size();
#else
  (void)ns;
  (void)bf;
  throw std::logic_error("a distributed partition needs a build with MPI");
#endif
}

const std::vector<std::uint32_t>& rows_around(RowPartition& p, const BondFamilies& bf, bool transpose) {
  if (p.around_generation == p.generation && p.around_transpose == transpose) return p.around;
  std::vector<char> needed(p.mine.begin(), p.mine.end());
  for (std::uint32_t i : p.owned) {
    if (transpose)
      for (std::uint64_t q = bf.t_offsets[i]; q < bf.t_offsets[i + 1]; ++q) needed[bf.t_owner[q]] = 1;
    else
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) needed[bf.neighbor[k]] = 1;
  }
  p.around.clear();
  for (std::size_t i = 0; i < needed.size(); ++i)
    if (needed[i]) p.around.push_back(static_cast<std::uint32_t>(i));
  p.around_generation = p.generation;
  p.around_transpose = transpose;
  return p.around;
}

std::vector<std::uint32_t> owned_rows(const RowPartition& p, const std::vector<std::uint32_t>* rows) {
  if (!rows) return p.owned;
  std::vector<std::uint32_t> out;
  for (std::uint32_t i : *rows)
    if (i < p.mine.size() && p.mine[i]) out.push_back(i);
  return out;
}

namespace {

constexpr std::uint64_t kNotHeld = ~std::uint64_t{0};

// Every computed row's force, and W and the breakable stretch when given, to every rank.
void share_all_rows(const RowPartition& p, NodeSet& ns, const std::vector<std::uint32_t>& rows,
                    bool full, std::vector<double>* W, std::vector<double>* stretch) {
  const int D = ns.dim;
  const bool with_w = W != nullptr, with_s = stretch != nullptr;
  const std::size_t per_row = static_cast<std::size_t>(D) + with_w + with_s;
  // Reused from pass to pass: the exchange of every step neither allocates nor clears them.
  static std::vector<double> values, all_values;
  values.resize(rows.size() * per_row);
  double* f[3] = {ns.f[0].data(), ns.f[1].data(), ns.f[2].data()};
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::uint32_t i = rows[k];
    double* v = &values[k * per_row];
    for (int d = 0; d < D; ++d) v[d] = f[d][i];
    if (with_w) v[D] = (*W)[i];
    if (with_s) v[D + with_w] = (*stretch)[i];
  }
  const std::vector<std::uint32_t> listed = full ? std::vector<std::uint32_t>{} : mpi::all_gather(rows);
  const std::vector<std::uint32_t>& all_rows = full ? p.all_owned : listed;
  static std::vector<int> value_counts;
  mpi::all_gather_into(values, all_values, &value_counts);
  // This rank's own segment already holds these values: only the others' rows are written.
  const std::size_t own_begin = mpi::own_offset(value_counts) / per_row;
  const std::size_t own_end = own_begin + rows.size();
  for (std::size_t k = 0; k < all_rows.size(); ++k) {
    if (k == own_begin) k = own_end;
    if (k >= all_rows.size()) break;
    const std::uint32_t i = all_rows[k];
    const double* v = &all_values[k * per_row];
    for (int d = 0; d < D; ++d) f[d][i] = v[d];
    if (with_w) (*W)[i] = v[D];
    if (with_s) (*stretch)[i] = v[D + with_w];
  }
}

}  // namespace

std::size_t share_force_pass(const RowPartition& p, NodeSet& ns, BondFamilies& bf,
                             const std::vector<std::uint32_t>& rows,
                             const std::vector<std::uint64_t>& broken_here,
                             std::vector<std::uint64_t>* log, std::vector<double>* W,
                             std::vector<double>* stretch) {
  // Which optional fields travel: agreed by all, so that every rank packs the same layout.
  const bool with_w = mpi::max(W != nullptr) > 0;
  const bool with_s = mpi::max(stretch != nullptr) > 0;
  const bool full = mpi::max(&rows != &p.owned) == 0;
  std::vector<double> w_scratch, s_scratch;
  if (with_w && !W) W = &w_scratch;
  if (with_s && !stretch) stretch = &s_scratch;
  const std::size_t n = ns.size();
  if (with_w) W->resize(n, 0.0);
  if (with_s) stretch->resize(n, -INFINITY);
  if (p.ghost_pass) {
    // The ranks' regions need their ghosts' forces only; the rest waits for a sync (energy
    // densities and stretches stay with their rows' owners, whose triggers read them).
    share_ghost_forces(p, ns);
  } else {
    share_all_rows(p, ns, rows, full, with_w ? W : nullptr, with_s ? stretch : nullptr);
  }
  // Each broken bond with its row: while the rows lie in id order, the last row that begins at
  // or before it; once events moved some, by matching the rows' ranges against the sorted bonds.
  std::vector<std::uint32_t> row_of_here(broken_here.size());
  const std::vector<std::uint64_t>& begins = bf.offsets;
  if (bf.ends.empty()) {
    for (std::size_t q = 0; q < broken_here.size(); ++q)
      row_of_here[q] = static_cast<std::uint32_t>(
          std::upper_bound(begins.begin(), begins.end(), broken_here[q]) - begins.begin() - 1);
  } else if (!broken_here.empty()) {
    std::vector<std::uint64_t> sorted_here(broken_here);
    std::sort(sorted_here.begin(), sorted_here.end());
    std::vector<std::uint32_t> row_sorted(sorted_here.size());
    for (std::uint32_t i : rows) {
      const auto lo = std::lower_bound(sorted_here.begin(), sorted_here.end(), bf.begin(i));
      const auto hi = std::lower_bound(lo, sorted_here.end(), bf.end(i));
      for (auto it = lo; it != hi; ++it) row_sorted[static_cast<std::size_t>(it - sorted_here.begin())] = i;
    }
    for (std::size_t q = 0; q < broken_here.size(); ++q)
      row_of_here[q] = row_sorted[static_cast<std::size_t>(
          std::lower_bound(sorted_here.begin(), sorted_here.end(), broken_here[q]) - sorted_here.begin())];
  }
  // The rows that lost bonds, with their new broken weight as the owner's kernel summed it.
  std::vector<std::uint32_t> hit(row_of_here);
  std::sort(hit.begin(), hit.end());
  hit.erase(std::unique(hit.begin(), hit.end()), hit.end());
  std::vector<double> hit_weight;
  for (std::uint32_t i : hit) hit_weight.push_back(ns.broken_weight[i]);
  // Bonds travel by name (row and place), which ranks holding other rows read alike
  // (parallel/held_rows.hpp).
  std::vector<std::uint64_t> names_here(broken_here.size());
  for (std::size_t q = 0; q < broken_here.size(); ++q)
    names_here[q] = bf.name(row_of_here[q], broken_here[q]);
  std::vector<int> counts;
  std::vector<std::uint64_t> broken = mpi::all_gather(names_here, &counts);
  std::vector<int> hit_counts;
  const std::vector<std::uint32_t> all_hit = mpi::all_gather(hit, &hit_counts);
  const std::vector<double> all_hit_weight = mpi::all_gather(hit_weight);
  // The others' bonds, still intact in this rank's copy, and their rows' weights.
  std::size_t at = 0, hat = 0;
  for (int r = 0; r < static_cast<int>(counts.size()); ++r) {
    const std::size_t end = at + static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]);
    const std::size_t hend = hat + static_cast<std::size_t>(hit_counts[static_cast<std::size_t>(r)]);
    const bool mine = r == mpi::rank();
    for (std::size_t q = at; q < end; ++q) {
      // The log names this rank's copies; a bond in a row it does not hold leaves it.
      std::uint64_t k = 0;
      const bool held = bf.named(broken[q], k);
      if (!mine && held) bf.beta[k] = -bf.beta[k];
      broken[q] = held ? k : kNotHeld;
    }
    if (!mine) {
      for (std::size_t q = hat; q < hend; ++q) ns.broken_weight[all_hit[q]] = all_hit_weight[q];
    }
    at = end;
    hat = hend;
  }
  if (log)
    for (std::uint64_t k : broken)
      if (k != kNotHeld) log->push_back(k);
  return broken.size();
}

}  // namespace periadapt
