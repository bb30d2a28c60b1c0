#include "run/snapshot_observer.hpp"

#include <cmath>

#include "run/snapshot_fields.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

SnapshotObserver::SnapshotObserver(const RunView& view) {
  const auto& out = view.deck.output;
  if (!view.write_files) return;
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
  vtu_->write(view.vv.time(), view.model.nodes,
              snapshot_fields(view.model, W, view.deck.output.stress));
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

void SnapshotObserver::restore(ArchiveReader& r, RunView&) {
  r.tag("VTUS");
  std::vector<std::pair<double, std::string>> entries(r.get<std::uint64_t>());
  for (auto& [t, f] : entries) {
    r.get(t);
    r.get(f);
  }
  if (vtu_) vtu_->resume(std::move(entries));
}

void SnapshotObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  if (!view.write_files) return;
  if (vtu_) res.pvd_path = vtu_->pvd_path();
  j["outputs"]["pvd"] = res.pvd_path;
}

}  // namespace periadapt
