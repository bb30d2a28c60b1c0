#include "parallel/held_rows.hpp"

#include <algorithm>
#include <stdexcept>

#include "parallel/mpi_env.hpp"

namespace periadapt {

bool can_hold_rows(const BondFamilies& bf) {
  return bf.ends.empty() && bf.t_offsets.empty() && bf.dual_force.empty() &&
         bf.live == bf.offsets.back();
}

namespace {

// The kept rows of one bond array, in a fresh array of their size; the whole one is freed, so
// that the peak holds the whole arrays and one kept array, not all of them twice.
template <class T>
void keep_rows(std::vector<T>& a, const BondFamilies& bf, const std::vector<std::uint32_t>& keep,
               std::uint64_t kept) {
  std::vector<T> h;
  h.reserve(kept);
  for (std::uint32_t i : keep) h.insert(h.end(), a.begin() + bf.begin(i), a.begin() + bf.end(i));
  std::vector<T>().swap(a);
  a = std::move(h);
}

}  // namespace

void hold_bond_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep) {
  if (!can_hold_rows(bf)) throw std::logic_error("held bond rows need contiguous rows");
  const std::size_t n = bf.num_nodes();
  std::uint64_t kept = 0;
  for (std::uint32_t i : keep) kept += bf.end(i) - bf.begin(i);
  p.whole_capacity = bf.neighbor.capacity();
  keep_rows(bf.neighbor, bf, keep, kept);
  keep_rows(bf.inv_length, bf, keep, kept);
  keep_rows(bf.beta, bf, keep, kept);
  if (bf.keeps_state) keep_rows(bf.state, bf, keep, kept);
  std::vector<std::uint64_t> offsets(n + 1, 0);
  std::size_t q = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool held = q < keep.size() && keep[q] == i;
    offsets[i + 1] = offsets[i] + (held ? bf.end(i) - bf.begin(i) : 0);
    q += held;
  }
  p.whole_offsets = std::move(bf.offsets);
  bf.offsets = std::move(offsets);
  bf.close_contiguous();
  p.rows_held = true;
  p.held_row_count = keep.size();
  // The partition stays the one these rows came from (refresh_partition compares the size).
  p.bonds = bf.neighbor.size();
}

BondFamilies build_held_families(RowPartition& p, const NodeSet& ns, const QuadratureSpec& q,
                                 bool region) {
  const std::size_t n = ns.size();
  // The rows' sizes alone (offsets, no bond arrays) are what the split weighs: each rank
  // counts a slice of the ids, and every rank gets every count.
  const auto P = static_cast<std::size_t>(mpi::size()), r = static_cast<std::size_t>(mpi::rank());
  const std::size_t lo = n * r / P, hi = n * (r + 1) / P;
  std::vector<char> slice(n, 0);
  std::fill(slice.begin() + static_cast<std::ptrdiff_t>(lo),
            slice.begin() + static_cast<std::ptrdiff_t>(hi), 1);
  const std::vector<std::uint64_t> counted = family_offsets(ns, q, &slice);
  std::vector<std::uint64_t> mine(hi - lo);
  for (std::size_t i = lo; i < hi; ++i) mine[i - lo] = counted[i + 1] - counted[i];
  const std::vector<std::uint64_t> all = mpi::all_gather(mine);  // in id order
  BondFamilies sizes;
  sizes.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) sizes.offsets[i + 1] = sizes.offsets[i] + all[i];
  sizes.close_contiguous();
  p.active = true;
  refresh_partition(p, ns, sizes);
  std::vector<char> keep(p.mine.begin(), p.mine.end());
  // LPS: the rows around its own (dilatations) and around those (the mutual-bond reach).
  if (region) grow_by_families(ns, q, keep, 2);
  BondFamilies bf = build_families(ns, q, 0.0, &keep);
  std::size_t held = 0;
  for (char c : keep) held += c != 0;
  p.whole_offsets = std::move(sizes.offsets);
  p.whole_capacity = p.whole_offsets.back();  // a serial build without refinement room
  p.rows_held = true;
  p.held_row_count = held;
  p.bonds = bf.neighbor.size();
  return bf;
}

void share_owned_values(const RowPartition& p, std::vector<double>& v,
                        const std::vector<std::uint32_t>* rows) {
  if (!rows) {
    std::vector<double> mine(p.owned.size());
    for (std::size_t q = 0; q < p.owned.size(); ++q) mine[q] = v[p.owned[q]];
    const std::vector<double> all = mpi::all_gather(mine);
    for (std::size_t q = 0; q < p.all_owned.size(); ++q) v[p.all_owned[q]] = all[q];
    return;
  }
  // The listed rows grouped by owner, in list order: what each rank sends, in rank order.
  std::vector<std::vector<std::uint32_t>> by_rank(static_cast<std::size_t>(mpi::size()));
  for (std::uint32_t i : *rows) by_rank[static_cast<std::size_t>(p.owner[i])].push_back(i);
  const std::vector<std::uint32_t>& own = by_rank[static_cast<std::size_t>(mpi::rank())];
  std::vector<double> mine(own.size());
  for (std::size_t q = 0; q < own.size(); ++q) mine[q] = v[own[q]];
  const std::vector<double> all = mpi::all_gather(mine);
  std::size_t at = 0;
  for (const auto& list : by_rank)
    for (std::uint32_t i : list) v[i] = all[at++];
}

void share_held_setup(const RowPartition& p, NodeSet& ns, const BondFamilies& bf,
                      std::size_t& precrack_bonds) {
  double cut = 0;
  for (std::uint32_t i : p.owned)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) cut += bf.beta[k] < 0.0f;
  share_owned_values(p, ns.family_weight);
  share_owned_values(p, ns.broken_weight);
  precrack_bonds = static_cast<std::size_t>(mpi::sum_real(cut));
}

std::uint64_t whole_bond_count(const RowPartition& p, const BondFamilies& bf) {
  return p.rows_held ? p.whole_offsets.back() : bf.num_bonds();
}

}  // namespace periadapt
