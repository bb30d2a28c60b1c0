#include "parallel/held_rows.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <stdexcept>
#include <type_traits>

#include "core/cell_grid.hpp"
#include "discretize/partial_volume.hpp"
#include "parallel/mpi_env.hpp"

namespace periadapt {

HeldReach held_reach(bool state_based, bool dual_horizon) {
  if (dual_horizon) return HeldReach::Radius;
  return state_based ? HeldReach::TwoFamilies : HeldReach::Own;
}

void grow_held_rows(const NodeSet& ns, const QuadratureSpec& q, std::vector<char>& rows,
                    HeldReach reach, const BondFamilies* bonds, const std::vector<char>* current) {
  if (reach == HeldReach::TwoFamilies) grow_by_families(ns, q, rows, 2, bonds, current);
  if (reach != HeldReach::Radius) return;
  double hmax = 0, dxmax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) {
      hmax = std::max(hmax, ns.horizon[i]);
      dxmax = std::max(dxmax, ns.spacing[i]);
    }
  const double r = quadrature_search_radius(q.rule, ns.dim, hmax, dxmax) * (1 + 1e-9);
  if (!(r > 0)) return;
  const CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, ns.size(), r);
  std::vector<char> grown(rows);
  std::vector<std::uint32_t> marked;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i]) marked.push_back(static_cast<std::uint32_t>(i));
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t k = 0; k < marked.size(); ++k) {
    const std::uint32_t i = marked[k];
    grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, r, [&](std::uint32_t j, double) {
      if (ns.flags[j] & kActive) std::atomic_ref<char>(grown[j]).store(1, std::memory_order_relaxed);
    });
  }
  rows = std::move(grown);
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

// The end of every way of holding rows: the partition stays the one these rows came from
// (refresh_partition compares the size), and a dual-horizon transpose, which names bond slots,
// and the plain LPS pairing's far-end factors are made again over the rows now held.
void finish_hold(RowPartition& p, BondFamilies& bf, std::size_t rows, const NodeSet& ns) {
  p.rows_held = true;
  p.held_row_count = rows;
  p.bonds = bf.neighbor.size();
  bf.dual_force.clear();
  if (!bf.t_offsets.empty()) build_transpose(bf);
  if (!bf.reverse_at.empty()) build_reverse(bf, ns);
}

// Keeps the rows `keep` (ascending, all present here) in contiguous arrays.
void compact_to(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep,
                const NodeSet& ns) {
  const std::size_t n = bf.num_nodes();
  std::uint64_t kept = 0;
  for (std::uint32_t i : keep) kept += bf.end(i) - bf.begin(i);
  keep_rows(bf.neighbor, bf, keep, kept);
  keep_rows(bf.inv_length, bf, keep, kept);
  keep_rows(bf.beta, bf, keep, kept);
  if (bf.keeps_state) keep_rows(bf.state, bf, keep, kept);
  std::vector<std::uint64_t> offsets(n + 1, 0);
  p.held.assign(n, 0);
  std::size_t q = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool held = q < keep.size() && keep[q] == i;
    offsets[i + 1] = offsets[i] + (held ? bf.end(i) - bf.begin(i) : 0);
    p.held[i] = held;
    q += held;
  }
  bf.offsets = std::move(offsets);
  bf.close_contiguous();
  finish_hold(p, bf, keep.size(), ns);
}

// Keeps the rows `keep` (ascending, all present here) where they are: each slides down over the
// rows let go, in the order of their places, so no array is copied whole (an event's rehold would
// otherwise hold two copies of a rank's rows). Rows then lie in no particular order (bf.ends).
void compact_in_place(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep,
                      const NodeSet& ns) {
  const std::size_t n = bf.num_nodes();
  if (bf.ends.empty()) bf.ends.assign(bf.offsets.begin() + 1, bf.offsets.end());
  std::vector<std::uint32_t> order(keep);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return bf.offsets[a] < bf.offsets[b]; });
  p.held.assign(n, 0);
  std::uint64_t at = 0;
  for (std::uint32_t i : order) {
    const std::uint64_t b = bf.offsets[i], e = bf.ends[i];
    if (b != at) {
      // at < b: a copy towards the front never overwrites what it has still to read.
      auto slide = [&](auto& a) { std::copy(a.begin() + b, a.begin() + e, a.begin() + at); };
      slide(bf.neighbor);
      slide(bf.inv_length);
      slide(bf.beta);
      if (bf.keeps_state) slide(bf.state);
    }
    bf.offsets[i] = at;
    bf.ends[i] = at + (e - b);
    at += e - b;
    p.held[i] = 1;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!p.held[i]) bf.offsets[i] = bf.ends[i] = at;
  bf.offsets[n] = at;
  bf.live = at;
  auto fit = [&](auto& a) {
    a.resize(at);
    // Rows handed to other ranks (a repartition) give their memory back.
    if (a.capacity() > 2 * at + 4096) a.shrink_to_fit();
  };
  fit(bf.neighbor);
  fit(bf.inv_length);
  fit(bf.beta);
  if (bf.keeps_state) fit(bf.state);
  finish_hold(p, bf, keep.size(), ns);
}

// Keeps the rows `keep` (ascending, all present here) and lets the others go: their entries
// become slack, the slack at the end of the arrays is cut off, and the arrays are compacted in
// place once the slack passes an eighth of the kept bonds, so that most events cost the rows
// they touched, not a pass over every bond (and the event's own search, which compacts into
// fresh arrays past a quarter, seldom has to).
void release_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep,
                  const NodeSet& ns) {
  const std::size_t n = bf.num_nodes();
  if (bf.ends.empty()) bf.ends.assign(bf.offsets.begin() + 1, bf.offsets.end());
  std::vector<char> kept(n, 0);
  for (std::uint32_t i : keep) kept[i] = 1;
  std::uint64_t end = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (kept[i]) {
      end = std::max(end, bf.ends[i]);
      continue;
    }
    bf.live -= bf.ends[i] - bf.offsets[i];
    bf.offsets[i] = bf.ends[i] = 0;
  }
  if (end - bf.live > bf.live / 8) {
    compact_in_place(p, bf, keep, ns);
    return;
  }
  bf.neighbor.resize(end);
  bf.inv_length.resize(end);
  bf.beta.resize(end);
  if (bf.keeps_state) bf.state.resize(end);
  bf.offsets[n] = end;
  p.held = std::move(kept);
  finish_hold(p, bf, keep.size(), ns);
}

// Whole row lengths as row begins (a prefix sum).
template <class Length>
std::vector<std::uint64_t> row_begins(std::size_t n, Length length) {
  std::vector<std::uint64_t> b(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) b[i + 1] = b[i] + length(i);
  return b;
}

// Rows' contents in flat arrays, for a gather: their lengths, then their bonds.
struct RowData {
  std::vector<std::uint64_t> length;
  std::vector<std::uint32_t> neighbor, beta;  // beta as its bits
  std::vector<double> inv_length, state;

  void add(const BondFamilies& bf, std::uint32_t i) {
    length.push_back(bf.end(i) - bf.begin(i));
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      neighbor.push_back(bf.neighbor[k]);
      beta.push_back(std::bit_cast<std::uint32_t>(bf.beta[k]));
      inv_length.push_back(bf.inv_length[k]);
      if (bf.keeps_state) state.push_back(bf.state[k]);
    }
  }
  // Every rank's, concatenated in rank order.
  RowData gathered() const {
    return {mpi::all_gather(length), mpi::all_gather(neighbor), mpi::all_gather(beta),
            mpi::all_gather(inv_length), mpi::all_gather(state)};
  }
  // to[r] to rank r; what every rank sent this one, concatenated in rank order.
  static RowData exchanged(std::vector<RowData>& to) {
    RowData got;
    auto send = [&](auto member) {
      std::vector<std::remove_reference_t<decltype(to[0].*member)>> per(to.size());
      for (std::size_t r = 0; r < to.size(); ++r) per[r] = std::move(to[r].*member);
      got.*member = mpi::all_to_all(per);
    };
    send(&RowData::length);
    send(&RowData::neighbor);
    send(&RowData::beta);
    send(&RowData::inv_length);
    send(&RowData::state);
    return got;
  }
};

// Reads gathered rows in order; installs those asked for at the end of the arrays.
class RowReader {
 public:
  // `incoming`: the bonds about to be installed, room for which is made in one step per array.
  RowReader(const RowData& d, BondFamilies& bf, std::uint64_t incoming) : d_(d), bf_(bf) {
    const std::uint64_t want = bf.neighbor.size() + incoming;
    auto room = [&](auto& a) {
      if (a.capacity() < want) a.reserve(want + want / 8);
    };
    room(bf.neighbor);
    room(bf.inv_length);
    room(bf.beta);
    if (bf.keeps_state) room(bf.state);
  }
  void next(std::uint32_t i, bool install) {
    const std::uint64_t len = d_.length.at(row_++);
    if (install) {
      if (bf_.ends.empty()) bf_.ends.assign(bf_.offsets.begin() + 1, bf_.offsets.end());
      const std::uint64_t at = bf_.neighbor.size();
      bf_.neighbor.insert(bf_.neighbor.end(), d_.neighbor.begin() + bond_, d_.neighbor.begin() + bond_ + len);
      bf_.inv_length.insert(bf_.inv_length.end(), d_.inv_length.begin() + bond_,
                            d_.inv_length.begin() + bond_ + len);
      for (std::uint64_t k = bond_; k < bond_ + len; ++k)
        bf_.beta.push_back(std::bit_cast<float>(d_.beta[k]));
      if (bf_.keeps_state)
        bf_.state.insert(bf_.state.end(), d_.state.begin() + bond_, d_.state.begin() + bond_ + len);
      bf_.live += len - (bf_.ends[i] - bf_.offsets[i]);
      bf_.offsets[i] = at;
      bf_.ends[i] = at + len;
      bf_.offsets.back() = bf_.neighbor.size();
    }
    bond_ += len;
  }

 private:
  const RowData& d_;
  BondFamilies& bf_;
  std::size_t row_ = 0;
  std::uint64_t bond_ = 0;
};

}  // namespace

void hold_bond_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep,
                    const NodeSet& ns) {
  std::vector<std::uint64_t> whole =
      row_begins(bf.num_nodes(), [&](std::size_t i) { return bf.end(i) - bf.begin(i); });
  p.whole_capacity = std::max<std::uint64_t>(whole.back(), bf.neighbor.capacity());
  compact_to(p, bf, keep, ns);
  p.whole_offsets = std::move(whole);
}

void publish_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& rows) {
  if (!p.rows_held) return;
  const int me = mpi::rank();
  RowData mine;
  for (std::uint32_t i : rows)
    if (p.owner[i] == me) mine.add(bf, i);
  const RowData all = mine.gathered();
  // Gathered in rank order: the rows grouped by owner, in list order within each.
  std::vector<std::uint32_t> order(rows);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return p.owner[a] < p.owner[b]; });
  std::uint64_t incoming = 0;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (!p.held[order[k]]) incoming += all.length[k];
  RowReader read(all, bf, incoming);
  for (std::uint32_t i : order) {
    const bool lacks = !p.held[i];
    read.next(i, lacks);
    p.held[i] = 1;
  }
}

void rehold_rows(RowPartition& p, const NodeSet& ns, BondFamilies& bf, const QuadratureSpec& q,
                 HeldReach reach) {
  const std::size_t n = ns.size();
  if (bf.num_nodes() != n) throw std::logic_error("held rows: the arrays miss the new nodes' rows");
  // Rows this rank has: whole arrays, or the held and published ones and the event's new rows.
  auto present = [&](std::size_t i) { return !p.rows_held || i >= p.held.size() || p.held[i]; };
  std::vector<std::uint64_t> whole = row_begins(n, [&](std::size_t i) {
    return present(i) ? bf.end(i) - bf.begin(i) : p.whole_offsets[i + 1] - p.whole_offsets[i];
  });
  const std::vector<int> before = p.owner;
  if (p.nodes != n) {
    // Owners from the whole model's rows (every rank weighs the same lengths).
    BondFamilies sizes;
    sizes.offsets = whole;
    sizes.close_contiguous();
    refresh_partition(p, ns, sizes);
  }
  std::vector<char> keep(p.mine.begin(), p.mine.end());
  // The rows this rank has are current (an event rebuilt its window on every rank): their lists
  // give their families without a search.
  std::vector<char> listed(n);
  for (std::size_t i = 0; i < n; ++i) listed[i] = present(i);
  grow_held_rows(ns, q, keep, reach, &bf, &listed);
  // What this rank lacks comes from the row's previous owner, which held it: each rank asks
  // those owners, and they answer, point to point (a repartition moves many rows).
  const auto P = static_cast<std::size_t>(mpi::size());
  std::vector<std::vector<std::uint32_t>> ask(P);
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i] && !present(i)) ask[static_cast<std::size_t>(before[i])].push_back(static_cast<std::uint32_t>(i));
  std::vector<int> counts;
  const std::vector<std::uint32_t> asked = mpi::all_to_all(ask, &counts);
  std::vector<RowData> reply(P);
  for (std::size_t r = 0, at = 0; r < P; ++r)
    for (int c = 0; c < counts[r]; ++c) reply[r].add(bf, asked[at++]);
  const RowData got = RowData::exchanged(reply);
  std::uint64_t incoming = 0;
  for (std::uint64_t len : got.length) incoming += len;
  RowReader read(got, bf, incoming);
  for (const auto& from : ask)
    for (std::uint32_t i : from) read.next(i, true);
  std::vector<std::uint32_t> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) kept.push_back(static_cast<std::uint32_t>(i));
  p.whole_capacity = whole.back();
  // From whole arrays (the first pass) a fresh copy of the kept rows frees the rest; held arrays
  // let the others' rows go where they are.
  if (p.rows_held)
    release_rows(p, bf, kept, ns);
  else
    compact_to(p, bf, kept, ns);
  p.whole_offsets = std::move(whole);
}

BondFamilies build_held_families(RowPartition& p, const NodeSet& ns, const QuadratureSpec& q,
                                 HeldReach reach) {
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
  grow_held_rows(ns, q, keep, reach);
  BondFamilies bf = build_families(ns, q, 0.0, &keep);
  std::size_t held = 0;
  for (char c : keep) held += c != 0;
  p.whole_offsets = std::move(sizes.offsets);
  p.whole_capacity = p.whole_offsets.back();  // a serial build without refinement room
  p.rows_held = true;
  p.held.assign(keep.begin(), keep.end());
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
  // Every rank lists the same rows, so none skips the gather alone (an LPS-dual pass without a
  // gathered break lists none).
  if (rows->empty()) return;
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

void share_owned_values(const RowPartition& p, std::vector<double>& v, int stride) {
  const auto s = static_cast<std::size_t>(stride);
  std::vector<double> mine;
  mine.reserve(p.owned.size() * s);
  for (std::uint32_t i : p.owned) mine.insert(mine.end(), v.begin() + s * i, v.begin() + s * (i + 1));
  const std::vector<double> all = mpi::all_gather(mine);
  for (std::size_t q = 0; q < p.all_owned.size(); ++q)
    std::copy(all.begin() + s * q, all.begin() + s * (q + 1), v.begin() + s * p.all_owned[q]);
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
