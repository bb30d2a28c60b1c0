#include "parallel/held_rows.hpp"

#include <algorithm>
#include <limits>
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

std::uint64_t whole_bond_index(const RowPartition& p, const BondFamilies& bf, std::uint32_t i,
                               std::uint64_t k) {
  return p.rows_held ? p.whole_offsets[i] + (k - bf.begin(i)) : k;
}

bool held_bond_index(const RowPartition& p, const BondFamilies& bf, std::uint64_t whole,
                     std::uint64_t& k) {
  if (!p.rows_held) {
    k = whole;
    return true;
  }
  const auto it = std::upper_bound(p.whole_offsets.begin(), p.whole_offsets.end(), whole);
  const auto i = static_cast<std::size_t>(it - p.whole_offsets.begin()) - 1;
  if (bf.end(i) == bf.begin(i)) return false;  // a row this rank does not hold
  k = bf.begin(i) + (whole - p.whole_offsets[i]);
  return true;
}

std::uint64_t whole_bond_count(const RowPartition& p, const BondFamilies& bf) {
  return p.rows_held ? p.whole_offsets.back() : bf.num_bonds();
}

BondFamilies gather_whole_bonds(const RowPartition& p, const BondFamilies& bf) {
  if (p.whole_offsets.back() > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("a checkpoint gathers every bond to rank 0, which MPI counts in int: "
                             "this model has more than 2^31 bonds");
  // Each owner's rows in ascending order, as every rank lists them in p.all_owned.
  std::vector<std::uint32_t> nbr;
  std::vector<double> inv, state;
  std::vector<float> beta;
  for (std::uint32_t i : p.owned) {
    const std::uint64_t b = bf.begin(i), e = bf.end(i);
    nbr.insert(nbr.end(), bf.neighbor.begin() + b, bf.neighbor.begin() + e);
    inv.insert(inv.end(), bf.inv_length.begin() + b, bf.inv_length.begin() + e);
    beta.insert(beta.end(), bf.beta.begin() + b, bf.beta.begin() + e);
    if (bf.keeps_state) state.insert(state.end(), bf.state.begin() + b, bf.state.begin() + e);
  }
  const std::vector<std::uint32_t> all_nbr = mpi::gather_to_root(nbr);
  const std::vector<double> all_inv = mpi::gather_to_root(inv);
  const std::vector<float> all_beta = mpi::gather_to_root(beta);
  const std::vector<double> all_state = mpi::gather_to_root(state);
  BondFamilies w;
  if (mpi::rank() != 0) return w;
  const std::uint64_t total = p.whole_offsets.back();
  w.offsets = p.whole_offsets;
  w.neighbor.reserve(p.whole_capacity);
  w.inv_length.reserve(p.whole_capacity);
  w.beta.reserve(p.whole_capacity);
  w.neighbor.resize(total);
  w.inv_length.resize(total);
  w.beta.resize(total);
  w.keeps_state = bf.keeps_state;
  if (w.keeps_state) {
    w.state.reserve(p.whole_capacity);
    w.state.resize(total);
  }
  std::uint64_t at = 0;
  for (std::uint32_t i : p.all_owned) {
    const std::uint64_t b = p.whole_offsets[i], len = p.whole_offsets[i + 1] - b;
    std::copy_n(all_nbr.begin() + at, len, w.neighbor.begin() + b);
    std::copy_n(all_inv.begin() + at, len, w.inv_length.begin() + b);
    std::copy_n(all_beta.begin() + at, len, w.beta.begin() + b);
    if (w.keeps_state) std::copy_n(all_state.begin() + at, len, w.state.begin() + b);
    at += len;
  }
  if (at != total || at != all_nbr.size())
    throw std::logic_error("held bond rows: the owners' rows do not cover the model");
  w.close_contiguous();
  return w;
}

}  // namespace periadapt
