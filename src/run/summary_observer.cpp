#include "parallel/mpi_env.hpp"
#include "run/summary_observer.hpp"

#include <omp.h>

#include "analysis/energy.hpp"
#include "parallel/held_rows.hpp"
#include "core/process_memory.hpp"
#include "io/atomic_output.hpp"
#include "run/checkpoint_file.hpp"
#include "run/output_regions.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

nlohmann::json ranks_json(const RowPartition& p, double owned_evaluations) {
  nlohmann::json j = {{"count", mpi::size()},
          {"partition", p.method == PartitionMethod::Rcb ? "rcb" : "hsfc"},
          {"partitions_made", p.partitions},
          {"events_kept_partition", p.extensions},
          {"rebalance_threshold", p.rebalance_threshold},
          {"work_imbalance", p.imbalance},
          {"owned_integration", p.ghost_mode},
          {"region_nodes_rank0", p.ghost_mode ? nlohmann::json(p.region.size()) : nlohmann::json(nullptr)},
          {"ghost_nodes_rank0", p.ghost_mode ? nlohmann::json(p.ghosts) : nlohmann::json(nullptr)},
          {"ghost_peers_rank0", p.ghost_mode ? nlohmann::json(p.peers.size()) : nlohmann::json(nullptr)},
          {"region_steps", p.region_steps},
          {"window_events", p.window_events},
          {"window_events_resynced", p.window_events_resynced},
          {"held_bond_rows", p.rows_held},
          {"bond_rows_rank0", p.rows_held ? nlohmann::json(p.held_row_count) : nlohmann::json(nullptr)}};
  if (owned_evaluations >= 0) {
    // The bonds each rank's rows evaluated over the run: the largest share over the mean
    // (collective).
    const double mean = mpi::sum_real(owned_evaluations) / mpi::size();
    const double most = mpi::max_real(owned_evaluations);
    j["evaluation_imbalance"] = mean > 0 ? most / mean : 1.0;
  }
  return j;
}

SummaryObserver::SummaryObserver(const RunView& view) : initial_nodes_(view.model.nodes.size()) {}

void SummaryObserver::save(ArchiveWriter& w) {
  w.tag("SUMM");
  w.put(std::uint64_t{initial_nodes_});
}

void SummaryObserver::restore(ArchiveReader& r, RunView&) {
  r.tag("SUMM");
  initial_nodes_ = r.get<std::uint64_t>();
}

void SummaryObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  const Model& m = view.model;
  const NodeSet& ns = m.nodes;
  const VelocityVerlet& vv = view.vv;
  const RunTotals& tot = view.totals;
  j["deck"] = view.deck.file;
  j["status"] = tot.status;
  if (tot.restarted) j["restarted_from_step"] = tot.restarted_from_step;
  if (tot.interrupted_by) {
    if (view.write_files) j["checkpoint"] = view.dir + "/" + kCheckpointName;
    j["interrupted_by_signal"] = tot.interrupted_by;
    j["steps_done"] = tot.steps_done;
  }
  j["dimension"] = ns.dim;
  std::size_t active = 0;
  double phi = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) {
      ++active;
      phi += ns.damage(i);
    }
  j["nodes"]["initial"] = initial_nodes_;
  j["nodes"]["final"] = active;
  j["nodes"]["slots"] = ns.size();
  j["bonds"] = whole_bond_count(m.partition, m.bonds);
  j["precrack_bonds"] = m.precrack_bonds;
  j["broken_bonds"] = vv.broken_bonds();
  if (!view.deck.output.regions.empty()) {
    std::vector<double> W;
    strain_energy(m, W);
    j["regions"] = regions_json(view.deck.output.regions, ns, W, ns.f);
  }
  j["damage_sum"] = phi;
  j["steps"] = vv.step_count();
  j["dt"] = tot.dt;
  j["dt_stable"] = tot.dt_stable;
  j["end_time_s"] = vv.time();
  j["threads"] = omp_get_max_threads();
  if (m.partition.active) j["ranks"] = ranks_json(m.partition, vv.owned_bond_evaluations());
  j["setup_time_s"] = tot.setup_s;
  j["solver_time_s"] = tot.solver_s;
  // Inside the run loop, besides the solver: sampling the history (energies, damage, crack tip)
  // and, part of it, writing the VTU snapshots and PNG pictures.
  j["sampling_time_s"] = tot.sampling_s;
  j["snapshot_output_time_s"] = view.output_seconds;
  // Multi-rate stepping: how many active nodes ended on a longer step than dt.
  if (vv.multirate()) {
    res.multirate_slow_nodes = vv.slow_nodes();
    j["multirate_slow_nodes"] = *res.multirate_slow_nodes;
  }
  res.steps = vv.step_count();
  res.wall_s = tot.wall_s;
  res.bond_evals_per_s = tot.solver_s > 0 ? vv.bond_evaluations() / tot.solver_s : 0.0;
  j["wall_time_s"] = tot.wall_s;
  j["bond_evals_per_s"] = res.bond_evals_per_s;
  j["bond_evaluations"] = vv.bond_evaluations();
  {
    // Resident memory of the model arrays, per bond and per node, and the process peak (which
    // also holds the transient family-build buffers and output buffers). Distributed runs: rank
    // 0's (with held bond rows, its own rows' bonds and the whole model's row index).
    const double nn = static_cast<double>(ns.size());
    const std::size_t per_node = model_bytes_per_node(m);
    const double step_s = vv.step_count() > 0 ? tot.solver_s / vv.step_count() : 0.0;
    j["memory"] = {{"bytes_per_bond", BondFamilies::bytes_per_bond()},
                   {"bytes_per_node", per_node},
                   {"model_bytes", static_cast<double>(m.bonds.bond_array_bytes()) +
                                       nn * static_cast<double>(per_node) +
                                       static_cast<double>(m.partition.whole_offsets.size() *
                                                           sizeof(std::uint64_t))},
                   {"peak_rss_bytes", peak_rss_bytes()},
                   {"rss_end_bytes", current_rss_bytes()}};
    // The rank that needs the most memory sizes a job's request (collective: every rank ends
    // its run here).
    if (mpi::distributed())
      j["memory"]["peak_rss_largest_rank_bytes"] =
          mpi::max_real(static_cast<double>(peak_rss_bytes()));
    j["family_build_time_s"] = m.family_build_seconds;
    j["family_build_in_steps"] = step_s > 0 ? m.family_build_seconds / step_s : 0.0;
  }
  j["material"] = {{"E", m.material.E},           {"nu", m.material.nu},
                   {"rho", m.material.rho},       {"G0", m.material.G0},
                   {"c0", m.material.c0},         {"s0", m.material.s0},
                   {"micromodulus", to_string(m.material.shape)},
                   {"wave_speed_m_s", m.material.wave_speed}};
  if (m.formulation.keeps_bond_history()) {
    j["material"]["formulation"] = m.formulation.name();
    j["material"]["onset_stretch"] = m.material.onset_stretch;
  }
  if (!m.block_materials.empty()) {
    // Block 0 is the material section; counts are of the active nodes at the end.
    std::vector<std::size_t> count(m.block_materials.size(), 0);
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) ++count[ns.block[i]];
    nlohmann::json blocks = nlohmann::json::array();
    for (std::size_t b = 0; b < m.block_materials.size(); ++b) {
      const MaterialLaw& l = m.block_materials[b];
      blocks.push_back({{"name", l.name}, {"E", l.E}, {"nu", l.nu}, {"rho", l.rho}, {"G0", l.G0},
                        {"s0", l.s0}, {"wave_speed_m_s", l.wave_speed}, {"nodes", count[b]}});
    }
    j["blocks"] = blocks;
  }
  j["grid"] = {{"spacing", m.grid_spacing}, {"horizon", m.horizon}};
  if (tot.status == "diverged") {
    const DivergenceError& e = vv.divergence();
    res.divergence = DivergenceReport{
        e.node, e.step, e.time, {ns.x[0][e.node], ns.x[1][e.node], ns.x[2][e.node]}, e.what};
    j["divergence"] = {{"node", e.node},
                       {"step", e.step},
                       {"time_s", e.time},
                       {"position", {ns.x[0][e.node], ns.x[1][e.node], ns.x[2][e.node]}},
                       {"reason", e.what}};
  }
  if (res.unstable_time_step) j["unstable_time_step"] = *res.unstable_time_step;
  for (const Impactor& im : m.impactors) {
    auto vec = [&](const Vec3& v) { return std::vector<double>(v.begin(), v.begin() + ns.dim); };
    j["impactors"].push_back({{"center_m", vec(im.center)},
                              {"velocity_m_s", vec(im.velocity)},
                              {"force_on_body_N", vec(scale(im.force, -1.0))},
                              {"kinetic_energy_J", im.kinetic_energy()}});
  }
  if (m.pdro.enabled) {
    const double checks = static_cast<double>(m.pdro.counters->checks.load());
    j["overlay"] = {{"n", m.pdro.n},
                    {"checks", m.pdro.counters->checks.load()},
                    {"breaks", m.pdro.counters->breaks.load()},
                    {"checks_per_bond_evaluation",
                     vv.bond_evaluations() > 0 ? checks / vv.bond_evaluations() : 0.0}};
  }
  if (view.write_files)
    write_file_atomically(view.dir + "/summary.json",
                          [&](std::ostream& o) { o << j.dump(2) << "\n"; });
}

}  // namespace periadapt
