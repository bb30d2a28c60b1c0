#include "run/refinement_log_observer.hpp"

#include <cmath>

#include <fmt/format.h>

#include "adapt/adaptor.hpp"
#include "analysis/refinement_coverage.hpp"

namespace periadapt {

RefinementLogObserver::RefinementLogObserver(const RunView& view) {
  if (view.write_files) out_ = StreamedOutput(view.dir + "/refinement.csv");
}

void RefinementLogObserver::on_start(RunView&) {
  if (out_.is_open())
    out_ << "step,time_s,trigger,identified,parents,children,active_nodes,bonds,"
            "momentum_change_rel,kinetic_before_J,kinetic_after_J,dt_stable_s,event_wall_s\n";
}

void RefinementLogObserver::on_event(RunView&, const RefinementEvent& e) {
  seconds_ += e.stats.seconds;
  if (!out_.is_open()) return;
  // |p_after - p_before| against sum m|v|: the net momentum of a symmetric problem is ~0.
  double dp = 0;
  for (int d = 0; d < 3; ++d) dp += std::pow(e.stats.momentum_after[d] - e.stats.momentum_before[d], 2);
  const double rel =
      e.stats.momentum_scale > 0 ? std::sqrt(dp) / e.stats.momentum_scale : std::sqrt(dp);
  out_ << fmt::format("{},{:.9e},{},{},{},{},{},{},{:.3e},{:.9e},{:.9e},{:.6e},{:.4f}\n", e.step,
                      e.time, e.trigger, e.identified, e.stats.parents, e.stats.children,
                      e.active_nodes, e.bonds, rel, e.stats.kinetic_before, e.stats.kinetic_after,
                      e.dt_stable, e.stats.seconds);
}

void RefinementLogObserver::save(ArchiveWriter& w) {
  w.tag("REFL");
  w.put(out_.is_open() ? out_.text_so_far() : std::string());
  w.put(seconds_);
}

void RefinementLogObserver::restore(ArchiveReader& r, RunView&) {
  r.tag("REFL");
  const auto text = r.get<std::string>();
  if (out_.is_open()) out_ << text;
  r.get(seconds_);
}

void RefinementLogObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  const NodeSet& ns = view.model.nodes;
  const Adaptor& a = *view.adaptor;
  std::size_t parents = 0;
  for (const auto& e : a.events())
    if (e.trigger != "coarsen") parents += e.stats.parents;
  int top = 0;
  std::size_t active = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) {
      top = std::max(top, static_cast<int>(ns.level[i]));
      ++active;
    }
  j["adapt"] = {{"events", a.events().size()},
                {"parents_refined", parents},
                {"nodes_added", a.nodes_added()},
                {"nodes_removed", a.nodes_removed()},
                {"finest_level", top},
                {"refinement_wall_s", seconds_}};
  // Coverage of the cracks by the refined zone, within one coarse horizon.
  const RefinementCoverage cov =
      refinement_coverage(ns, view.deck.output.tip_threshold, view.model.horizon);
  j["adapt"]["refined_nodes"] = cov.refined;
  j["adapt"]["refined_far_from_cracks"] = cov.refined_far_from_cracks;
  j["adapt"]["cracked_nodes"] = cov.cracked;
  j["adapt"]["cracked_coarse_nodes"] = cov.cracked_coarse;
  j["nodes"]["active"] = active;
  out_.finish();
}

}  // namespace periadapt
