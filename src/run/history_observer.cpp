#include "run/history_observer.hpp"

#include <fmt/format.h>

#include "analysis/energy.hpp"
#include "parallel/held_rows.hpp"
#include "run/crack_tip_observer.hpp"
#include "run/output_regions.hpp"
#include "run/resultants.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

HistoryObserver::HistoryObserver(RunView& view, const CrackTipObserver* tip)
    : tip_(tip), every_(view.deck.output.history_every), total_(view.total_steps) {
  if (view.write_files) out_ = StreamedOutput(view.dir + "/history.csv");
}

void HistoryObserver::on_start(RunView& view) {
  if (!out_.is_open()) return;
  rank_column_ = view.model.partition.active;
  out_ << "step,time_s,kinetic_energy_J,strain_energy_J,external_work_J,energy_balance_J,"
          "broken_bonds,damaged_nodes,damage_sum,tip_x_m,tip_y_m,tip_z_m,tip_speed_m_s,nodes,"
          "bonds," + resultant_header(view.model) +
              region_header(view.deck.output.regions, view.model.nodes.dim) +
              (rank_column_ ? "rank_imbalance," : "") + "wall_time_s\n";
}

bool HistoryObserver::wants_energy_density(long step) const {
  return step % every_ == 0 || step == total_;
}

void HistoryObserver::on_step(RunView& view, long step, bool closing) {
  if (!view.history_due(step, closing)) return;
  const NodeSet& ns = view.model.nodes;
  const VelocityVerlet& vv = view.vv;
  // Every rank takes part in the sums (collective), rank 0 writes them.
  const RowPartition* part = view.model.partition.active ? &view.model.partition : nullptr;
  U_ = view.strain_energy();
  K_ = kinetic_energy(ns, part);
  W_ext_ = vv.external_work();
  sample_step_ = step;
  sample_time_ = vv.time();
  damaged_nodes_ = 0;
  damage_sum_ = 0;
  std::size_t active = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    ++active;
    const double phi = ns.damage(i);
    damage_sum_ += phi;
    if (phi > view.deck.output.tip_threshold) ++damaged_nodes_;
  }
  const std::string resultants = resultant_columns(
      view.model, [&](const BodyLoad& l) { return vv.applied_force(l); },
      [&](const PrescribedMotion& p) { return vv.reaction_force(p); }, part);
  const std::string regions =
      region_columns(view.deck.output.regions, ns, view.energy_density(), ns.f, part);
  if (!out_.is_open()) return;
  const Vec3 tip = tip_ ? tip_->last_tip() : Vec3{NAN, NAN, NAN};
  const double speed = tip_ ? tip_->current_speed() : 0.0;
  out_ << fmt::format(
      "{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{},{}{}{}{:.4f}\n",
      step, vv.time(), K_, U_, W_ext_, K_ + U_ - W_ext_, vv.broken_bonds(),
      damaged_nodes_, damage_sum_, tip[0], tip[1], tip[2], speed, active,
      whole_bond_count(view.model.partition, view.model.bonds), resultants, regions,
      rank_column_ ? fmt::format("{:.4f},", view.model.partition.imbalance) : std::string(),
      view.elapsed_s());
}

void HistoryObserver::save(ArchiveWriter& w) {
  w.tag("HIST");
  w.put(out_.is_open() ? out_.text_so_far() : std::string());
  w.put(K_);
  w.put(U_);
  w.put(std::uint64_t{damaged_nodes_});
  w.put(damage_sum_);
  w.put(W_ext_);
  w.put(sample_time_);
  w.put(std::int64_t{sample_step_});
}

void HistoryObserver::restore(ArchiveReader& r, RunView&) {
  r.tag("HIST");
  const auto text = r.get<std::string>();
  // The columns the checkpointed run chose go on, whatever the rank count now.
  rank_column_ = text.substr(0, text.find('\n')).find("rank_imbalance") != std::string::npos;
  if (out_.is_open()) out_ << text;
  r.get(K_);
  r.get(U_);
  damaged_nodes_ = r.get<std::uint64_t>();
  r.get(damage_sum_);
  r.get(W_ext_);
  r.get(sample_time_);
  sample_step_ = static_cast<long>(r.get<std::int64_t>());
}

void HistoryObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  j["energy"] = {{"kinetic_J", K_}, {"strain_J", U_}, {"external_work_J", W_ext_},
                 {"step", sample_step_}, {"time_s", sample_time_}};
  if (!out_.is_open()) return;
  if (view.deck.output.load_displacement)
    write_load_displacement_png(view.dir, out_.text_so_far(), *view.deck.output.load_displacement,
                                view.model);
  res.history_path = view.dir + "/history.csv";
  j["outputs"]["history"] = res.history_path;
  out_.finish();
}

}  // namespace periadapt
