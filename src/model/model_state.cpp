#include "model/model_state.hpp"

#include <string>

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
}  // namespace

void save_model_state(ArchiveWriter& w, const Model& m) {
  auto put = [&](const auto& v) { w.put(v); };
  w.tag("NODE");
  w.put(m.nodes.dim);
  node_arrays(put, m.nodes);
  w.tag("BOND");
  bond_arrays(put, m.bonds);
  // The arrays' room decides when a refinement event compacts them: kept, so a restarted run
  // allocates as the uninterrupted one does.
  w.put(std::uint64_t{m.bonds.neighbor.capacity()});
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

void restore_model_state(ArchiveReader& r, Model& m) {
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
  m.bonds = BondFamilies{};  // its capacity is the checkpoint's, not the fresh build's
  bond_arrays(get, m.bonds);
  const BondFamilies& bf = m.bonds;
  if (bf.offsets.size() != n + 1 || (!bf.ends.empty() && bf.ends.size() != n) ||
      bf.neighbor.size() < bf.offsets.back() || bf.inv_length.size() != bf.neighbor.size() ||
      bf.beta.size() != bf.neighbor.size() ||
      bf.state.size() != (bf.keeps_state ? bf.neighbor.size() : 0))
    throw ArchiveError("the checkpoint's bond arrays do not fit its nodes (corrupt)");
  for (std::uint32_t j : bf.neighbor)
    if (j >= n) throw ArchiveError("the checkpoint's bonds name a node it does not hold (corrupt)");
  const auto room = r.get<std::uint64_t>();
  if (room < bf.neighbor.size() || room > 4 * bf.neighbor.size() + 4096)
    throw ArchiveError("the checkpoint's bond array room is out of range (corrupt)");
  m.bonds.neighbor.reserve(room);
  m.bonds.inv_length.reserve(room);
  m.bonds.beta.reserve(room);
  if (m.bonds.keeps_state) m.bonds.state.reserve(room);
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
