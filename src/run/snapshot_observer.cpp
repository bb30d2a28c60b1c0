#include "run/snapshot_observer.hpp"

#include <cmath>

#include "parallel/mpi_env.hpp"
#include "run/snapshot_fields.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

SnapshotObserver::SnapshotObserver(const RunView& view) : pieces_(mpi::distributed()) {
  const auto& out = view.deck.output;
  // Distributed runs: every rank writes its piece.
  if (!view.write_files && !pieces_) return;
  vtu_ = std::make_unique<VtuSeries>(view.dir, "snapshot", out.vtu_zlib);
  if (out.vtu && out.vtu_count > 0)
    for (int k = 0; k <= out.vtu_count; ++k)
      steps_.insert(static_cast<long>(
          std::llround(static_cast<double>(k) * view.total_steps / out.vtu_count)));
}

bool SnapshotObserver::wants_energy_density(long step) const {
  return vtu_ && steps_.count(step) > 0;
}

void SnapshotObserver::on_step(RunView& view, long step, bool closing) {
  if (!vtu_ || (steps_.count(step) > 0) == closing) return;
  const std::vector<double>& W = view.energy_density();
  const auto t0 = RunView::clock::now();
  const NodeSet& ns = view.model.nodes;
  std::vector<PointField> fields = snapshot_fields(view.model, W, view.deck.output.stress);
  if (!pieces_) {
    vtu_->write(view.vv.time(), ns, fields);
  } else {
    // This rank's active rows (rank 0 also takes nodes no partition has seen yet).
    const std::vector<int>& owner = view.model.partition.owner;
    const int me = mpi::rank();
    std::vector<std::uint32_t> ids;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if ((ns.flags[i] & kActive) && (i < owner.size() ? owner[i] == me : me == 0))
        ids.push_back(static_cast<std::uint32_t>(i));
    // Which rank computes each node's forces (the partition, for ParaView).
    PointField rank{"rank", 1, std::vector<double>(ns.size(), 0.0)};
    for (std::size_t i = 0; i < owner.size(); ++i) rank.data[i] = owner[i];
    fields.push_back(std::move(rank));
    vtu_->write_piece(view.vv.time(), ns, ids, fields, me);
    mpi::max(0L);  // every piece is on disk before the PVTU names it
    if (view.write_files) vtu_->write_parallel_index(fields, mpi::size());
  }
  view.output_seconds += std::chrono::duration<double>(RunView::clock::now() - t0).count();
}

void SnapshotObserver::save(ArchiveWriter& w) {
  w.tag("VTUS");
  const auto& entries = vtu_ ? vtu_->entries() : std::vector<std::pair<double, std::string>>{};
  w.put(std::uint64_t{entries.size()});
  for (const auto& [t, f] : entries) {
    w.put(t);
    w.put(f);
  }
}

void SnapshotObserver::restore(ArchiveReader& r, RunView& view) {
  r.tag("VTUS");
  std::vector<std::pair<double, std::string>> entries(r.get<std::uint64_t>());
  for (auto& [t, f] : entries) {
    r.get(t);
    r.get(f);
  }
  if (vtu_) vtu_->resume(std::move(entries), view.write_files);
}

void SnapshotObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  if (!view.write_files) return;
  // No collection is named where no snapshot was written (output.vtu: false).
  if (vtu_ && !vtu_->entries().empty()) res.pvd_path = vtu_->pvd_path();
  if (!res.pvd_path.empty()) j["outputs"]["pvd"] = res.pvd_path;
}

}  // namespace periadapt
