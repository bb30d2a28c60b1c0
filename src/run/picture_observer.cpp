#include "run/picture_observer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "io/damage_png.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

bool is_damage_picture(const std::string& name) {
  return name.rfind("damage_", 0) == 0 && name.size() > 13 &&
         name.compare(name.size() - 6, 6, "us.png") == 0;
}

PictureObserver::PictureObserver(const RunView& view, double dt) {
  for (double t : view.deck.output.png_times)
    steps_.insert(std::clamp<long>(static_cast<long>(std::llround(t / dt)), 0, view.total_steps));
  steps_.insert(view.total_steps);
}

void PictureObserver::on_step(RunView& view, long step, bool closing) {
  if (!view.write_files || (steps_.count(step) > 0) == closing) return;
  const auto t0 = RunView::clock::now();
  const NodeSet& ns = view.model.nodes;
  const double t = view.vv.time();
  std::vector<double> dmg(ns.size());
  std::size_t active = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    dmg[i] = ns.damage(i);
    active += (ns.flags[i] & kActive) != 0;
  }
  PngOptions po;
  po.width = view.deck.output.png_width;
  po.title = fmt::format("damage at t = {:.2f} us   ({} nodes)", t * 1e6, active);
  const std::string p = fmt::format("{}/damage_{:08.3f}us.png", view.dir, t * 1e6);
  write_field_png(p, ns, dmg, po);
  written_.push_back(p);
  view.output_seconds += std::chrono::duration<double>(RunView::clock::now() - t0).count();
}

void PictureObserver::save(ArchiveWriter& w) {
  w.tag("PNGS");
  w.put(std::uint64_t{written_.size()});
  for (const std::string& p : written_) w.put(std::filesystem::path(p).filename().string());
}

void PictureObserver::restore(ArchiveReader& r, RunView& view) {
  r.tag("PNGS");
  written_.resize(r.get<std::uint64_t>());
  std::set<std::string> kept;
  for (std::string& p : written_) {
    const std::string name = r.get<std::string>();
    kept.insert(name);
    p = view.dir + "/" + name;
  }
  if (!view.write_files) return;
  // The stopped run drew its last state after the checkpoint; the restarted run goes on past it,
  // so that picture would stand beside the ones an uninterrupted run leaves.
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(view.dir, ec)) {
    const std::string name = e.path().filename().string();
    if (is_damage_picture(name) && !kept.count(name)) fs::remove(e.path(), ec);
  }
}

void PictureObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  if (view.write_files) j["outputs"]["png"] = written_;
}

}  // namespace periadapt
