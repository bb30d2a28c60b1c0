#include "model/model_state.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <utility>
#include <stdexcept>
#include <string>

#include "discretize/families.hpp"
#include "parallel/held_rows.hpp"

namespace periadapt {

namespace {
template <class Archive, class NS>
void node_arrays(Archive& a, NS& ns) {
  a(ns.x);
  a(ns.u);
  a(ns.v);
  a(ns.a);
  a(ns.f);
  a(ns.cur);
  a(ns.volume);
  a(ns.spacing);
  a(ns.horizon);
  a(ns.micromodulus);
  a(ns.critical_stretch);
  a(ns.density);
  a(ns.broken_weight);
  a(ns.family_weight);
  a(ns.level);
  a(ns.parent);
  a(ns.flags);
  a(ns.block);
}

template <class Archive, class BF>
void bond_arrays(Archive& a, BF& bf) {
  a(bf.offsets);
  a(bf.ends);
  a(bf.live);
  a(bf.neighbor);
  a(bf.inv_length);
  a(bf.beta);
  a(bf.keeps_state);
  a(bf.state);
  a(bf.t_offsets);
  a(bf.t_owner);
  a(bf.t_bond);
  a(bf.dual_force);
}

template <class Archive, class M>
void scratch_arrays(Archive& a, M& m) {
  a(m.precrack_bonds);
  a(m.track_breakable_stretch);
  a(m.breakable_stretch);
  a(m.lps_scratch.m);
  a(m.lps_scratch.theta);
  a(m.lps_scratch.reach);
  a(m.lps_scratch.packed);
}

constexpr std::uint8_t kBondsInline = 0, kBondsInPieces = 1;

// Whole bond arrays as a checkpoint holds them inline: consistent with n nodes.
void check_whole_arrays(const BondFamilies& bf, std::size_t n, std::uint64_t room) {
  if (bf.offsets.size() != n + 1 || (!bf.ends.empty() && bf.ends.size() != n) ||
      bf.neighbor.size() < bf.offsets.back() || bf.inv_length.size() != bf.neighbor.size() ||
      bf.beta.size() != bf.neighbor.size() ||
      bf.state.size() != (bf.keeps_state ? bf.neighbor.size() : 0))
    throw ArchiveError("the checkpoint's bond arrays do not fit its nodes (corrupt)");
  for (std::uint32_t j : bf.neighbor)
    if (j >= n) throw ArchiveError("the checkpoint's bonds name a node it does not hold (corrupt)");
  if (room < bf.neighbor.size() || room > 4 * bf.neighbor.size() + 4096)
    throw ArchiveError("the checkpoint's bond array room is out of range (corrupt)");
}

// Row begins of contiguous whole arrays: n + 1 ascending values from 0.
void check_offsets(const std::vector<std::uint64_t>& offsets, std::size_t n) {
  bool ok = offsets.size() == n + 1 && offsets[0] == 0;
  for (std::size_t i = 0; ok && i < n; ++i) ok = offsets[i] <= offsets[i + 1];
  if (!ok) throw ArchiveError("the checkpoint's bond rows do not fit its nodes (corrupt)");
}

// Whether held arrays take row i: they hold it (each held row is as long as the whole row, the
// others are empty).
bool holds_row(const BondFamilies& to, std::size_t i) { return to.end(i) > to.begin(i); }

// The whole model's rows as the checkpoint records them, against the held rows built for this
// run (the same deck and no refinement: the same rows).
void check_held_layout(const Model& m, const std::vector<std::uint64_t>& offsets,
                       bool keeps_state) {
  if (offsets != m.partition.whole_offsets)
    throw ArchiveError("the checkpoint's bond rows differ from the model's (another model?)");
  if (keeps_state != m.bonds.keeps_state)
    throw ArchiveError("the checkpoint and the deck differ in the bond law's history");
}

// Reads the pieces a checkpoint names into `to` (whole arrays sized by `offsets`, or held rows),
// those with rows it takes only; each holds exactly the rows the checkpoint gives it.
void read_pieces(ArchiveReader& r, BondFamilies& to, const std::vector<std::uint64_t>& offsets,
                 bool whole, const PieceReader& read_piece) {
  const std::size_t n = offsets.size() - 1;
  const auto count = r.get<std::uint64_t>();
  if (count < 1 || count > n + 1)
    throw ArchiveError("the checkpoint names " + std::to_string(count) + " bond pieces (corrupt)");
  std::vector<std::string> files(count);
  for (std::string& f : files) r.get(f);
  std::vector<std::uint64_t> sums;
  r.get(sums);
  if (sums.size() != count)
    throw ArchiveError("the checkpoint's bond pieces lack checksums (corrupt)");
  std::vector<int> piece_of;
  r.get(piece_of);
  if (piece_of.size() != n)
    throw ArchiveError("the checkpoint's row pieces do not fit its nodes (corrupt)");
  std::vector<char> wanted(count, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (piece_of[i] < 0 || static_cast<std::uint64_t>(piece_of[i]) >= count)
      throw ArchiveError("the checkpoint names a bond piece out of range (corrupt)");
    wanted[static_cast<std::size_t>(piece_of[i])] |= whole || holds_row(to, i);
  }
  if (!read_piece) throw ArchiveError("the checkpoint keeps its bond rows in pieces: no reader");
  std::vector<char> seen(n, 0);
  for (std::size_t k = 0; k < count; ++k) {
    if (!wanted[k]) continue;
    read_piece(files[k], sums[k], [&](ArchiveStream& s) {
      char tag[4];
      s.read(tag, sizeof tag);
      if (std::memcmp(tag, "ROWS", 4) != 0) throw ArchiveError(files[k] + ": not a bond piece");
      if (s.get<std::uint64_t>() != n)
        throw ArchiveError(files[k] + ": a piece of a model with another node count");
      const auto count_rows = s.get<std::uint64_t>();
      if (count_rows > n) throw ArchiveError(files[k] + ": more rows than the model (corrupt)");
      std::vector<std::uint32_t> rows(count_rows);
      s.read(rows.data(), rows.size() * sizeof(std::uint32_t));
      std::uint64_t total = 0;
      for (std::uint32_t i : rows) {
        if (i >= n || seen[i] || static_cast<std::size_t>(piece_of[i]) != k)
          throw ArchiveError(files[k] + ": names a row of another piece (corrupt)");
        seen[i] = 1;
        total += offsets[i + 1] - offsets[i];
      }
      // Each array row by row: into its place where `to` takes the row, skipped where not.
      auto array = [&](auto& into, bool present) {
        using T = typename std::decay_t<decltype(into)>::value_type;
        if (s.get<std::uint64_t>() != (present ? total : 0))
          throw ArchiveError(files[k] + ": its bond arrays do not fit its rows (corrupt)");
        if (!present) return;
        for (std::uint32_t i : rows) {
          const std::uint64_t len = offsets[i + 1] - offsets[i];
          if (whole || holds_row(to, i)) s.read(into.data() + to.begin(i), len * sizeof(T));
          else s.skip(len * sizeof(T));
        }
      };
      array(to.neighbor, true);
      array(to.inv_length, true);
      array(to.beta, true);
      array(to.state, to.keeps_state);
      for (std::uint32_t i : rows)
        if (whole || holds_row(to, i))
          for (std::uint64_t q = to.begin(i); q < to.end(i); ++q)
            if (to.neighbor[q] >= n)
              throw ArchiveError(files[k] + ": a bond names a node the model lacks (corrupt)");
    });
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!seen[i] && wanted[static_cast<std::size_t>(piece_of[i])])
      throw ArchiveError(files[static_cast<std::size_t>(piece_of[i])] + ": misses row " +
                         std::to_string(i) + " (corrupt)");
}

// An adaptive run's held rows: its node set is the checkpoint's, not the deck's, so the rows
// the set-up split are let go and the checkpoint's rows are split afresh (collective). Returns
// this rank's rows to hold (LPS: with those within two families).
std::vector<std::uint32_t> split_restored_rows(Model& m, const std::vector<std::uint64_t>& offsets) {
  RowPartition& p = m.partition;
  m.bonds = BondFamilies{};
  BondFamilies sizes;
  sizes.offsets = offsets;
  sizes.close_contiguous();
  p.owner.clear();
  p.nodes = 0;
  refresh_partition(p, m.nodes, sizes);
  std::vector<char> keep(p.mine.begin(), p.mine.end());
  grow_held_rows(m.nodes, m.quadrature, keep,
                 held_reach(m.formulation.state_based(), m.formulation.dual_horizon));
  std::vector<std::uint32_t> rows;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) rows.push_back(static_cast<std::uint32_t>(i));
  return rows;
}

// The bond section: inline whole arrays or pieces, into whole or held arrays.
void restore_bonds(ArchiveReader& r, Model& m, const PieceReader& read_piece) {
  const std::size_t n = m.nodes.size();
  auto get = [&](auto& v) { r.get(v); };
  const bool held = m.partition.rows_held;
  const auto layout = r.get<std::uint8_t>();
  if (layout == kBondsInline) {
    BondFamilies whole;
    bond_arrays(get, whole);
    const auto room = r.get<std::uint64_t>();
    check_whole_arrays(whole, n, room);
    if (!held) {
      m.bonds = std::move(whole);  // its capacity is the checkpoint's, not the fresh build's
      m.bonds.neighbor.reserve(room);
      m.bonds.inv_length.reserve(room);
      m.bonds.beta.reserve(room);
      if (m.bonds.keeps_state) m.bonds.state.reserve(room);
      return;
    }
    // A checkpoint of a run that held the whole arrays (a serial one), continued with held rows.
    if (m.partition.refining) {
      if (whole.keeps_state != m.bonds.keeps_state)
        throw ArchiveError("the checkpoint's bond rows differ from the model's (another model?)");
      std::vector<std::uint64_t> lengths(n + 1, 0);
      for (std::size_t i = 0; i < n; ++i) lengths[i + 1] = lengths[i] + whole.end(i) - whole.begin(i);
      const std::vector<std::uint32_t> keep = split_restored_rows(m, lengths);
      hold_bond_rows(m.partition, whole, keep, m.nodes);
      m.bonds = std::move(whole);
      m.partition.whole_capacity = room;
      return;
    }
    if (!whole.ends.empty())
      throw ArchiveError("the checkpoint's bond rows differ from the model's (another model?)");
    check_held_layout(m, whole.offsets, whole.keeps_state);
    for (std::size_t i = 0; i < n; ++i) {
      if (!holds_row(m.bonds, i)) continue;
      auto copy = [&](const auto& from, auto& into) {
        std::copy(from.begin() + static_cast<std::ptrdiff_t>(whole.begin(i)),
                  from.begin() + static_cast<std::ptrdiff_t>(whole.end(i)),
                  into.begin() + static_cast<std::ptrdiff_t>(m.bonds.begin(i)));
      };
      copy(whole.neighbor, m.bonds.neighbor);
      copy(whole.inv_length, m.bonds.inv_length);
      copy(whole.beta, m.bonds.beta);
      if (whole.keeps_state) copy(whole.state, m.bonds.state);
    }
    m.partition.whole_capacity = room;
    return;
  }
  if (layout != kBondsInPieces)
    throw ArchiveError("unknown bond layout " + std::to_string(layout) + " (corrupt)");
  std::vector<std::uint64_t> offsets;
  r.get(offsets);
  check_offsets(offsets, n);
  const bool keeps_state = r.get<std::uint8_t>() != 0;
  const auto room = r.get<std::uint64_t>();
  const std::uint64_t total = offsets.back();
  if (room < total || room > 4 * total + 4096)
    throw ArchiveError("the checkpoint's bond array room is out of range (corrupt)");
  if (held && m.partition.refining) {
    if (keeps_state != m.bonds.keeps_state)
      throw ArchiveError("the checkpoint and the deck differ in the bond law's history");
    RowPartition& p = m.partition;
    const std::vector<std::uint32_t> keep = split_restored_rows(m, offsets);
    BondFamilies& bf = m.bonds;
    bf.keeps_state = keeps_state;
    bf.offsets.assign(n + 1, 0);
    p.held.assign(n, 0);
    for (std::uint32_t i : keep) p.held[i] = 1;
    for (std::size_t i = 0; i < n; ++i)
      bf.offsets[i + 1] = bf.offsets[i] + (p.held[i] ? offsets[i + 1] - offsets[i] : 0);
    bf.neighbor.resize(bf.offsets[n]);
    bf.inv_length.resize(bf.offsets[n]);
    bf.beta.resize(bf.offsets[n]);
    if (keeps_state) bf.state.resize(bf.offsets[n]);
    bf.close_contiguous();
    p.rows_held = true;
    p.held_row_count = keep.size();
    p.whole_offsets = offsets;
    p.whole_capacity = room;
    p.bonds = bf.neighbor.size();
    read_pieces(r, bf, offsets, false, read_piece);
    if (m.formulation.dual_horizon) build_transpose(bf);
    return;
  }
  if (held) {
    check_held_layout(m, offsets, keeps_state);
    m.partition.whole_capacity = room;
    read_pieces(r, m.bonds, offsets, false, read_piece);
    return;
  }
  BondFamilies& bf = m.bonds;
  bf = BondFamilies{};
  bf.neighbor.reserve(room);
  bf.inv_length.reserve(room);
  bf.beta.reserve(room);
  bf.neighbor.resize(total);
  bf.inv_length.resize(total);
  bf.beta.resize(total);
  bf.keeps_state = keeps_state;
  if (keeps_state) {
    bf.state.reserve(room);
    bf.state.resize(total);
  }
  bf.offsets = std::move(offsets);
  bf.close_contiguous();
  read_pieces(r, bf, bf.offsets, true, read_piece);
  // Pieces keep rows only: the dual-horizon transpose is made from them.
  if (m.formulation.dual_horizon) build_transpose(bf);
}
}  // namespace

void write_bond_rows_piece(const Model& m, const ArchiveSink& out) {
  const RowPartition& p = m.partition;
  const BondFamilies& bf = m.bonds;
  auto value = [&](std::uint64_t v) { out(reinterpret_cast<const char*>(&v), sizeof v); };
  std::uint64_t total = 0;
  for (std::uint32_t i : p.owned) total += bf.end(i) - bf.begin(i);
  out("ROWS", 4);
  value(bf.num_nodes());
  value(p.owned.size());
  out(reinterpret_cast<const char*>(p.owned.data()), p.owned.size() * sizeof(std::uint32_t));
  auto rows_of = [&](const auto& a, bool present) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    value(present ? total : 0);
    if (!present) return;
    for (std::uint32_t i : p.owned)
      out(reinterpret_cast<const char*>(a.data() + bf.begin(i)),
          (bf.end(i) - bf.begin(i)) * sizeof(T));
  };
  rows_of(bf.neighbor, true);
  rows_of(bf.inv_length, true);
  rows_of(bf.beta, true);
  rows_of(bf.state, bf.keeps_state);
}

void save_model_state(ArchiveWriter& w, const Model& m, const BondPieces* pieces) {
  auto put = [&](const auto& v) { w.put(v); };
  w.tag("NODE");
  w.put(m.nodes.dim);
  node_arrays(put, m.nodes);
  w.tag("BOND");
  // The arrays' room decides when a refinement event compacts them: kept, so a restarted run
  // allocates as the uninterrupted one does.
  const RowPartition& p = m.partition;
  if (p.rows_held) {
    if (!pieces) throw std::logic_error("a checkpoint of held bond rows needs their pieces");
    w.put<std::uint8_t>(kBondsInPieces);
    w.put(p.whole_offsets);
    w.put<std::uint8_t>(m.bonds.keeps_state);
    w.put(std::uint64_t{p.whole_capacity});
    w.put(std::uint64_t{pieces->files.size()});
    for (const std::string& f : pieces->files) w.put(f);
    w.put(pieces->sums);
    w.put(p.owner);  // each row's piece: a restart reads only the pieces with its rows
  } else {
    w.put<std::uint8_t>(kBondsInline);
    bond_arrays(put, m.bonds);
    w.put(std::uint64_t{m.bonds.neighbor.capacity()});
  }
  w.tag("LOAD");
  w.put(std::uint64_t{m.loads.size()});
  for (const BodyLoad& l : m.loads) w.put(l.nodes);
  w.put(std::uint64_t{m.motions.size()});
  for (const PrescribedMotion& pm : m.motions) w.put(pm.nodes);
  w.tag("SCRT");
  scratch_arrays(put, m);
  w.put(std::uint64_t{m.pdro.counters ? m.pdro.counters->checks.load() : 0});
  w.put(std::uint64_t{m.pdro.counters ? m.pdro.counters->breaks.load() : 0});
}

void restore_model_state(ArchiveReader& r, Model& m, const PieceReader& read_piece) {
  auto get = [&](auto& v) { r.get(v); };
  r.tag("NODE");
  const int dim = r.get<int>();
  if (dim != m.nodes.dim)
    throw ArchiveError("the checkpoint holds a " + std::to_string(dim) + "D model, the deck a " +
                       std::to_string(m.nodes.dim) + "D one");
  node_arrays(get, m.nodes);
  const std::size_t n = m.nodes.size();
  bool consistent = m.nodes.cur.size() == 4 * n;
  for (int d = 0; d < 3; ++d)
    consistent = consistent && m.nodes.x[d].size() == n && m.nodes.u[d].size() == n &&
                 m.nodes.v[d].size() == n && m.nodes.a[d].size() == n && m.nodes.f[d].size() == n;
  for (std::size_t s : {m.nodes.spacing.size(), m.nodes.horizon.size(), m.nodes.micromodulus.size(),
                        m.nodes.critical_stretch.size(), m.nodes.density.size(),
                        m.nodes.broken_weight.size(), m.nodes.family_weight.size(),
                        m.nodes.level.size(), m.nodes.parent.size(), m.nodes.flags.size()})
    consistent = consistent && s == n;
  consistent = consistent && (m.nodes.block.empty() || m.nodes.block.size() == n) &&
               m.nodes.block.empty() == m.block_materials.empty();
  for (std::uint8_t b : m.nodes.block)
    consistent = consistent && b < m.block_materials.size();
  if (!consistent) throw ArchiveError("the checkpoint's node arrays differ in length (corrupt)");
  r.tag("BOND");
  restore_bonds(r, m, read_piece);
  // The plain LPS pairing's far-end factors are not archived: made from the rows restored.
  if (!m.formulation.dual_horizon) index_pairs(m.bonds, m.nodes, false, m.formulation.state_based());
  r.tag("LOAD");
  if (r.get<std::uint64_t>() != m.loads.size())
    throw ArchiveError("the checkpoint's number of loads differs from the deck's");
  for (BodyLoad& l : m.loads) r.get(l.nodes);
  if (r.get<std::uint64_t>() != m.motions.size())
    throw ArchiveError("the checkpoint's number of boundary conditions differs from the deck's");
  for (PrescribedMotion& pm : m.motions) r.get(pm.nodes);
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes)
      if (i >= n) throw ArchiveError("a load of the checkpoint names a node it does not hold");
  for (const PrescribedMotion& pm : m.motions)
    for (std::uint32_t i : pm.nodes)
      if (i >= n) throw ArchiveError("a boundary condition of the checkpoint names a node it does not hold");
  r.tag("SCRT");
  scratch_arrays(get, m);
  const auto checks = r.get<std::uint64_t>(), breaks = r.get<std::uint64_t>();
  if (m.pdro.counters) {
    m.pdro.counters->checks = checks;
    m.pdro.counters->breaks = breaks;
  }
  // The ghost-force table is a function of the families: built whole at the next force pass,
  // equal to the one the uninterrupted run built event by event.
  m.ghost.rebuild_all = true;
  m.ghost.pending.clear();
}

}  // namespace periadapt
