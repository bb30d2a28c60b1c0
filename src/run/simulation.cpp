#include "run/simulation.hpp"
#include "run/output_regions.hpp"
#include "run/snapshot_fields.hpp"
#include "run/resultants.hpp"
#include "io/line_plot.hpp"
#include "adapt/adaptor.hpp"

#include "core/process_memory.hpp"

#include <omp.h>

#include <chrono>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "analysis/crack_tip.hpp"
#include "run/checkpoint_file.hpp"
#include "core/binary_archive.hpp"
#include "model/model_state.hpp"
#include "analysis/energy.hpp"
#include "analysis/refinement_coverage.hpp"
#include "run/interrupt.hpp"
#include "run/progress.hpp"
#include "io/atomic_output.hpp"
#include "io/damage_png.hpp"
#include "input/deck_error.hpp"
#include "io/vtu_writer.hpp"
#include "setup/build_model.hpp"
#include "solver/stable_time_step.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

namespace {
// A fresh run into a used folder: the files of the earlier run that this one might not
// overwrite (more snapshots or pictures, a refinement log, a checkpoint) would mix with its own.
void remove_earlier_run_outputs(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    auto starts = [&](const char* p) { return name.rfind(p, 0) == 0; };
    auto ends = [&](const char* q) {
      const std::size_t n = std::strlen(q);
      return name.size() >= n && name.compare(name.size() - n, n, q) == 0;
    };
    if ((starts("snapshot_") && ends(".vtu")) || (starts("damage_") && ends("us.png")) ||
        name == kCheckpointName || name == "refinement.csv" || name == "crack_speed.csv" ||
        name == "crack_speed.png" || name == "load_displacement.png")
      fs::remove(e.path(), ec);
  }
}

std::string resultant_columns(const Model& m, const VelocityVerlet& vv) {
  return periadapt::resultant_columns(
      m, [&](const BodyLoad& l) { return vv.applied_force(l); },
      [&](const PrescribedMotion& p) { return vv.reaction_force(p); });
}

std::size_t active_count(const NodeSet& ns) {
  std::size_t n = 0;
  for (auto f : ns.flags) n += (f & kActive) != 0;
  return n;
}
}  // namespace

TimeStepChoice choose_time_step(const Deck& dk, const Model& m) {
  const StableStep s = stable_time_step(m);
  TimeStepChoice c{0, s.dt, s.node, 0, 1.0};
  if (dk.adapt.enabled && dk.solver == Deck::SolverType::Explicit) {
    // The stable step scales with the horizon (sum_j C_ij V_j ~ c delta^(dim-1) ~ 1/delta^2):
    // the finest level's bound applies from the first event on, so it is checked (and the
    // default step chosen) now rather than when the first refinement happens. Relative to the
    // horizon of the node that limits the step now: after an initial refinement that node may
    // already be on a finer level.
    const double h_lim = m.nodes.horizon[s.node];
    for (int l = 1; l <= dk.adapt.max_level; ++l)
      c.level_ratio = std::min(c.level_ratio, level_horizon(m, dk.adapt, l) / h_lim);
  }
  if (dk.time_step) {
    if (*dk.time_step > s.dt && !dk.allow_unstable_time_step)
      throw DeckError(dk.file, 0, 0, "solver.time_step",
                      fmt::format("{:.4g} s exceeds the stable time step {:.4g} s (Silling-Askari "
                                  "bound, limited by node {}); use a smaller value or set "
                                  "solver.allow_unstable_time_step: true",
                                  *dk.time_step, s.dt, s.node));
    if (*dk.time_step > s.dt * c.level_ratio * (1 + 1e-9) && !dk.allow_unstable_time_step)
      throw DeckError(dk.file, 0, 0, "solver.time_step",
                      fmt::format("{:.4g} s exceeds the stable step expected at refinement level "
                                  "{} (about {:.4g} s = {:.4g} x the level-0 bound); lower it, "
                                  "leave it out (the default accounts for the finest level), "
                                  "or lower adapt.max_level",
                                  *dk.time_step, dk.adapt.max_level, s.dt * c.level_ratio,
                                  c.level_ratio));
    c.dt = *dk.time_step;
  } else {
    c.dt = dk.safety * s.dt * c.level_ratio;
  }
  if (!std::isfinite(c.dt) || c.dt <= 0)
    throw DeckError(dk.file, 0, 0, "solver", "no stable time step: the model has no bonds");
  // Range-checked before any conversion: a step count beyond this is no run anyone can wait for,
  // and one below 1 would end "done" with nothing done.
  constexpr double kMaxSteps = 1e10;
  const double steps = dk.steps ? static_cast<double>(*dk.steps) : std::ceil(dk.end_time / c.dt - 1e-9);
  if (!(steps >= 1) || !(steps <= kMaxSteps))
    throw DeckError(dk.file, 0, 0, dk.steps ? "solver.steps" : "solver.end_time",
                    fmt::format("gives {:.4g} steps of {:.4g} s; a run takes 1 ... {:.0e} steps "
                                "(end_time / time_step)",
                                steps > 0 ? steps : 0.0, c.dt, kMaxSteps));
  c.steps = static_cast<long>(steps);
  return c;
}


RunResult run_simulation(const Deck& dk, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  RunResult res;
  Model& m = res.model;
  m = build_model(dk);
  const double t_setup = std::chrono::duration<double>(clock::now() - t_start).count();
  const TimeStepChoice ts = choose_time_step(dk, m);
  const NodeSet& ns = m.nodes;
  std::size_t nodes0 = ns.size();

  const std::string dir = opt.out_dir ? *opt.out_dir : dk.output.directory;
  if (opt.write_files) std::filesystem::create_directories(dir);
  // A restart reads its checkpoint before anything is written (a mismatch changes nothing).
  std::optional<Checkpoint> restart;
  std::optional<ArchiveReader> state;
  if (opt.restart) {
    restart = read_checkpoint(*opt.restart, dk);
    state.emplace(restart->payload, restart->path);
    try {
      restore_model_state(*state, m);
    } catch (const ArchiveError& e) {
      throw DeckError(restart->path, 0, 0, "--restart", e.what());
    }
    if (restart->info.threads != omp_get_max_threads() && !opt.quiet)
      fmt::print("note: the checkpoint was written with {} threads, this run has {}: it continues "
                 "correctly, but not bit for bit\n",
                 restart->info.threads, omp_get_max_threads());
  } else if (opt.write_files) {
    remove_earlier_run_outputs(dir);
  }
  if (!opt.quiet) {
    fmt::print("PeriAdapt: {} nodes, {} bonds ({} cut by pre-cracks), {}D {}{}, c0 = {:.4e}, "
               "s0 = {:.4e}\n",
               ns.size(), m.bonds.num_bonds(), m.precrack_bonds, ns.dim,
               m.formulation.label(), m.formulation.dual_horizon ? " (dual horizon)" : "",
               m.material.c0, m.material.s0);
    fmt::print("time step {:.4e} s (stable bound {:.4e} s), {} steps, {} threads{}\n", ts.dt,
               ts.dt_crit, ts.steps, omp_get_max_threads(),
               dk.multirate ? fmt::format("; multi-rate: nodes stable at k dt take it, k <= {}",
                                          dk.multirate_ratio)
                            : std::string());
  }

  // Crack-tip tracker.
  CrackTipOptions tip;
  const bool track = dk.output.track_tip && ns.dim >= 2;
  if (track) {
    tip.threshold = dk.output.tip_threshold;
    if (!dk.cracks.empty()) {
      const Vec3 a = dk.cracks[0].points[0], b = dk.cracks[0].points[1];
      tip.origin = b;
      tip.direction = scale(sub(b, a), 1.0 / norm(sub(b, a)));
    }
    if (dk.output.tip_origin) tip.origin = *dk.output.tip_origin;
    if (dk.output.tip_direction) tip.direction = *dk.output.tip_direction;
    tip.side = dk.output.tip_side == "upper"   ? CrackTipOptions::Side::Upper
               : dk.output.tip_side == "lower" ? CrackTipOptions::Side::Lower
                                               : CrackTipOptions::Side::Both;
    tip.window = dk.output.tip_window;
    tip.advance = dk.output.tip_advance ? *dk.output.tip_advance : m.grid_spacing;
    tip.column = m.grid_spacing;
    tip.branch_gap = dk.output.branch_gap ? *dk.output.branch_gap : m.horizon;
    // Two grid spacings bridge the gaps a crack band has on any level; the pre-crack's own band
    // within a horizon of its tip starts the crack.
    tip.link = 2.0 * m.grid_spacing;
    tip.seed_radius = m.horizon;
  }
  CrackTipTracker tracker(tip);

  // Output schedule.
  std::set<long> vtu_steps, png_steps;
  if (dk.output.vtu && dk.output.vtu_count > 0)
    for (int k = 0; k <= dk.output.vtu_count; ++k)
      vtu_steps.insert(static_cast<long>(std::llround(static_cast<double>(k) * ts.steps /
                                                      dk.output.vtu_count)));
  for (double t : dk.output.png_times)
    png_steps.insert(std::clamp<long>(static_cast<long>(std::llround(t / ts.dt)), 0, ts.steps));
  png_steps.insert(ts.steps);

  std::unique_ptr<VtuSeries> vtu;
  StreamedOutput hist;
  if (opt.write_files) {
    vtu = std::make_unique<VtuSeries>(dir, "snapshot", dk.output.vtu_zlib);
    hist = StreamedOutput(dir + "/history.csv");
    if (!restart)
      hist << "step,time_s,kinetic_energy_J,strain_energy_J,external_work_J,energy_balance_J,"
              "broken_bonds,damaged_nodes,damage_sum,tip_x_m,tip_y_m,tip_z_m,tip_speed_m_s,nodes,"
              "bonds," + resultant_header(m) + region_header(dk.output.regions, ns.dim) +
                  "wall_time_s\n";
  }
  std::vector<double> W;
  std::vector<std::string> pngs;

  VelocityVerlet vv(m, ts.dt);
  if (dk.multirate) vv.set_multirate(dk.safety, dk.multirate_ratio);
  if (!restart) vv.initialize();
  double solver_seconds = 0;
  std::size_t damaged_nodes = 0;
  double damage_sum = 0;  // total damage over active nodes (Stewart & Jeon Fig. 9a)
  Vec3 last_tip{NAN, NAN, NAN};
  double K = 0, U = 0;

  double observe_seconds = 0, output_seconds = 0;  // history/tracker sampling; VTU and PNG files
  // `last`: the run stops after this step (interrupted): the history row, snapshot and picture
  // of it that the schedule did not give already.
  auto observe = [&](long step, bool last = false) {
    const auto t_obs = clock::now();
    struct AddElapsed {
      clock::time_point t0;
      double& acc;
      ~AddElapsed() { acc += std::chrono::duration<double>(clock::now() - t0).count(); }
    } obs_timer{t_obs, observe_seconds};
    const double t = vv.time();
    const bool hist_due = step % dk.output.history_every == 0 || step == ts.steps;
    const bool vtu_due = vtu_steps.count(step) > 0, png_due = png_steps.count(step) > 0;
    const bool do_hist = last ? !hist_due : hist_due;
    const bool do_vtu = vtu && (last ? !vtu_due : vtu_due);
    const bool do_png = opt.write_files && (last ? !png_due : png_due);
    if (!(do_hist || do_vtu || do_png)) return;
    if (do_hist || do_vtu) {
      // From the step's own force pass when it was asked for (see the loop), else a bond pass.
      if (const std::vector<double>* w = vv.energy_density_now()) {
        W = *w;
        U = strain_energy_of(ns, W);
      } else {
        U = strain_energy(m, W);
      }
    }
    if (do_hist) {
      K = kinetic_energy(ns);
      damaged_nodes = 0;
      damage_sum = 0;
      for (std::size_t i = 0; i < ns.size(); ++i) {
        if (!(ns.flags[i] & kActive)) continue;
        const double phi = ns.damage(i);
        damage_sum += phi;
        if (phi > tip.threshold) ++damaged_nodes;
      }
      if (track) {
        if (auto s = tracker.observe(ns, t)) last_tip = s->position;
      }
      if (hist.is_open())
        hist << fmt::format(
            "{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{},{}{}{:.4f}\n",
            step, t, K, U, vv.external_work(), K + U - vv.external_work(), vv.broken_bonds(),
            damaged_nodes, damage_sum, last_tip[0], last_tip[1], last_tip[2], tracker.current_speed(),
            active_count(ns), m.bonds.num_bonds(), resultant_columns(m, vv),
            region_columns(dk.output.regions, ns, W, ns.f),
            std::chrono::duration<double>(clock::now() - t_start).count());
    }
    const auto t_out = clock::now();
    AddElapsed out_timer{t_out, output_seconds};
    if (do_vtu) vtu->write(t, ns, snapshot_fields(m, W, dk.output.stress));
    if (do_png) {
      std::vector<double> dmg(ns.size());
      for (std::size_t i = 0; i < ns.size(); ++i) dmg[i] = ns.damage(i);
      PngOptions po;
      po.width = dk.output.png_width;
      po.title = fmt::format("damage at t = {:.2f} us   ({} nodes)", t * 1e6, active_count(ns));
      const std::string p = fmt::format("{}/damage_{:08.3f}us.png", dir, t * 1e6);
      write_field_png(p, ns, dmg, po);
      pngs.push_back(p);
    }
  };

  std::unique_ptr<Adaptor> adaptor;
  StreamedOutput refinement_log;
  std::size_t events_logged = 0;
  double adapt_seconds = 0;
  if (dk.adapt.enabled) {
    adaptor = std::make_unique<Adaptor>(m, vv, dk.adapt);
    if (opt.write_files) {
      refinement_log = StreamedOutput(dir + "/refinement.csv");
      if (!restart)
        refinement_log << "step,time_s,trigger,identified,parents,children,active_nodes,bonds,"
                          "momentum_change_rel,kinetic_before_J,kinetic_after_J,dt_stable_s,"
                          "event_wall_s\n";
    }
  }
  auto log_events = [&]() {
    if (!adaptor) return;
    const auto& evs = adaptor->events();
    for (; events_logged < evs.size(); ++events_logged) {
      const RefinementEvent& e = evs[events_logged];
      adapt_seconds += e.stats.seconds;
      // |p_after - p_before| against sum m|v|: the net momentum of a symmetric problem is ~0.
      double dp = 0;
      for (int d = 0; d < 3; ++d)
        dp += std::pow(e.stats.momentum_after[d] - e.stats.momentum_before[d], 2);
      const double rel = e.stats.momentum_scale > 0 ? std::sqrt(dp) / e.stats.momentum_scale : std::sqrt(dp);
      if (refinement_log.is_open())
        refinement_log << fmt::format("{},{:.9e},{},{},{},{},{},{},{:.3e},{:.9e},{:.9e},{:.6e},{:.4f}\n",
                                      e.step, e.time, e.trigger, e.identified, e.stats.parents,
                                      e.stats.children, e.active_nodes, e.bonds, rel,
                                      e.stats.kinetic_before, e.stats.kinetic_after, e.dt_stable,
                                      e.stats.seconds);
    }
  };

  // Checkpoints: the state after a step and its scheduled outputs; the run's own files so far
  // travel inside, so a restart rewrites them as they were at that step.
  auto save_run_state = [&](ArchiveWriter& w) {
    save_model_state(w, m);
    vv.save_state(w);
    w.put<std::uint8_t>(adaptor != nullptr);
    if (adaptor) adaptor->save_state(w);
    tracker.save_state(w);
    w.tag("OUTS");
    w.put(std::uint64_t{nodes0});
    w.put(hist.is_open() ? hist.text_so_far() : std::string());
    w.put(refinement_log.is_open() ? refinement_log.text_so_far() : std::string());
    w.put(std::uint64_t{events_logged});
    const auto& entries = vtu ? vtu->entries() : std::vector<std::pair<double, std::string>>{};
    w.put(std::uint64_t{entries.size()});
    for (const auto& [t, f] : entries) {
      w.put(t);
      w.put(f);
    }
    w.put(std::uint64_t{pngs.size()});
    for (const std::string& p : pngs) w.put(std::filesystem::path(p).filename().string());
    w.put(last_tip);
    w.put(K);
    w.put(U);
    w.put(std::uint64_t{damaged_nodes});
    w.put(damage_sum);
    w.put(solver_seconds);
    w.put(observe_seconds);
    w.put(output_seconds);
    w.put(adapt_seconds);
  };
  auto restore_run_state = [&](ArchiveReader& r) {
    vv.restore_state(r);
    if (r.get<std::uint8_t>() != (adaptor != nullptr))
      throw ArchiveError("the checkpoint and the deck differ in adapt");
    if (adaptor) adaptor->restore_state(r);
    tracker.restore_state(r);
    r.tag("OUTS");
    nodes0 = r.get<std::uint64_t>();
    const auto history = r.get<std::string>(), refinements = r.get<std::string>();
    if (hist.is_open()) hist << history;
    if (refinement_log.is_open()) refinement_log << refinements;
    events_logged = r.get<std::uint64_t>();
    std::vector<std::pair<double, std::string>> entries(r.get<std::uint64_t>());
    for (auto& [t, f] : entries) {
      r.get(t);
      r.get(f);
    }
    if (vtu) vtu->resume(std::move(entries));
    pngs.resize(r.get<std::uint64_t>());
    for (std::string& p : pngs) p = dir + "/" + r.get<std::string>();
    r.get(last_tip);
    r.get(K);
    r.get(U);
    damaged_nodes = r.get<std::uint64_t>();
    r.get(damage_sum);
    r.get(solver_seconds);
    r.get(observe_seconds);
    r.get(output_seconds);
    r.get(adapt_seconds);
    if (!r.at_end()) throw ArchiveError("the checkpoint has data past its last section");
  };
  auto write_run_checkpoint = [&]() {
    ArchiveWriter w;
    save_run_state(w);
    CheckpointInfo info{build_id(), deck_fingerprint(dk), dk.file, omp_get_max_threads(),
                        vv.step_count(), vv.time()};
    write_checkpoint(dir + "/" + kCheckpointName, info, w.bytes());
  };

  if (restart) {
    try {
      restore_run_state(*state);
    } catch (const ArchiveError& e) {
      throw DeckError(restart->path, 0, 0, "--restart", e.what());
    }
    if (!opt.quiet)
      fmt::print("restarted from {} at step {} (t = {:.6e} s)\n", restart->path, vv.step_count(),
                 vv.time());
  } else {
    observe(0);
  }
  const long first_step = vv.step_count() + 1;
  Progress bar(ts.steps, opt.quiet);
  for (long s = first_step; s <= ts.steps; ++s) {
    const auto t0 = clock::now();
    if (s % dk.output.history_every == 0 || s == ts.steps || (vtu && vtu_steps.count(s)))
      vv.request_energy_at(s);
    bool ok = false;
    try {
      ok = adaptor ? adaptor->step() : vv.step();
    } catch (const UnstableAfterRefinement& e) {
      log_events();
      throw DeckError(dk.file, 0, 0, "solver.time_step", e.what());
    }
    solver_seconds += std::chrono::duration<double>(clock::now() - t0).count();
    log_events();
    if (!ok) {
      res.diverged = true;
      break;
    }
    res.interrupted = interrupt_signal();
    observe(s);
    if (opt.write_files && (res.interrupted || (dk.output.checkpoint_every > 0 &&
                                                s % dk.output.checkpoint_every == 0 && s < ts.steps)))
      write_run_checkpoint();
    if (res.interrupted) observe(s, true);
    bar.update(s, track && tracker.initiation_time()
                      ? fmt::format("tip v = {:.0f} m/s", tracker.current_speed())
                      : "");
    if (res.interrupted) {
      res.steps_done = s;
      break;
    }
  }
  bar.finish();
  const double wall = std::chrono::duration<double>(clock::now() - t_start).count();

  nlohmann::json& j = res.summary;
  j["deck"] = dk.file;
  j["status"] = res.diverged ? "diverged" : res.interrupted ? "interrupted" : "completed";
  if (restart) j["restarted_from_step"] = first_step - 1;
  if (res.interrupted && opt.write_files) j["checkpoint"] = dir + "/" + kCheckpointName;
  if (res.interrupted) {
    j["interrupted_by_signal"] = res.interrupted;
    j["steps_done"] = res.steps_done;
  }
  j["dimension"] = ns.dim;
  j["nodes"] = {{"initial", nodes0}, {"final", active_count(ns)}, {"slots", ns.size()}};
  j["bonds"] = m.bonds.num_bonds();
  j["precrack_bonds"] = m.precrack_bonds;
  j["broken_bonds"] = vv.broken_bonds();
  if (!dk.output.regions.empty()) {
    strain_energy(m, W);
    j["regions"] = regions_json(dk.output.regions, ns, W, ns.f);
  }
  {
    double phi = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) phi += ns.damage(i);
    j["damage_sum"] = phi;
  }
  j["steps"] = vv.step_count();
  j["dt"] = ts.dt;
  j["dt_stable"] = ts.dt_crit;
  j["end_time_s"] = vv.time();
  j["threads"] = omp_get_max_threads();
  j["setup_time_s"] = t_setup;
  j["solver_time_s"] = solver_seconds;
  // Inside the run loop, besides the solver: sampling the history (energies, damage, crack tip)
  // and, part of it, writing the VTU snapshots and PNG pictures.
  j["sampling_time_s"] = observe_seconds;
  j["snapshot_output_time_s"] = output_seconds;
  // Multi-rate stepping: how many active nodes ended on a longer step than dt.
  if (vv.multirate()) j["multirate_slow_nodes"] = vv.slow_nodes();
  j["wall_time_s"] = wall;
  j["bond_evals_per_s"] = solver_seconds > 0 ? vv.bond_evaluations() / solver_seconds : 0.0;
  j["bond_evaluations"] = vv.bond_evaluations();
  {
    // Resident memory of the model arrays, per bond and per node, and the process peak (which
    // also holds the transient family-build buffers and output buffers).
    const double nn = static_cast<double>(ns.size());
    const std::size_t per_node = model_bytes_per_node(m);
    const double step_s = vv.step_count() > 0 ? solver_seconds / vv.step_count() : 0.0;
    j["memory"] = {{"bytes_per_bond", BondFamilies::bytes_per_bond()},
                   {"bytes_per_node", per_node},
                   {"model_bytes", static_cast<double>(m.bonds.bond_array_bytes()) +
                                       nn * static_cast<double>(per_node)},
                   {"peak_rss_bytes", peak_rss_bytes()}};
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
  j["grid"] = {{"spacing", m.grid_spacing}, {"horizon", m.horizon}};
  if (adaptor) {
    std::size_t parents = 0;
    for (const auto& e : adaptor->events())
      if (e.trigger != "coarsen") parents += e.stats.parents;
    int top = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) top = std::max(top, static_cast<int>(ns.level[i]));
    j["adapt"] = {{"events", adaptor->events().size()},
                  {"parents_refined", parents},
                  {"nodes_added", adaptor->nodes_added()},
                  {"nodes_removed", adaptor->nodes_removed()},
                  {"finest_level", top},
                  {"refinement_wall_s", adapt_seconds}};
    // Coverage of the cracks by the refined zone, within one coarse horizon.
    const RefinementCoverage cov = refinement_coverage(ns, tip.threshold, m.horizon);
    j["adapt"]["refined_nodes"] = cov.refined;
    j["adapt"]["refined_far_from_cracks"] = cov.refined_far_from_cracks;
    j["adapt"]["cracked_nodes"] = cov.cracked;
    j["adapt"]["cracked_coarse_nodes"] = cov.cracked_coarse;
    j["nodes"]["active"] = active_count(ns);
  }
  j["energy"] = {{"kinetic_J", K}, {"strain_J", U}, {"external_work_J", vv.external_work()}};
  if (res.diverged) {
    const DivergenceError& e = vv.divergence();
    j["divergence"] = {{"node", e.node},
                       {"step", e.step},
                       {"time_s", e.time},
                       {"position", {ns.x[0][e.node], ns.x[1][e.node], ns.x[2][e.node]}},
                       {"reason", e.what}};
  }
  if (m.pdro.enabled) {
    const double checks = static_cast<double>(m.pdro.counters->checks.load());
    j["overlay"] = {{"n", m.pdro.n},
                    {"checks", m.pdro.counters->checks.load()},
                    {"breaks", m.pdro.counters->breaks.load()},
                    {"checks_per_bond_evaluation",
                     vv.bond_evaluations() > 0 ? checks / vv.bond_evaluations() : 0.0}};
  }
  if (track) {
    nlohmann::json c;
    c["threshold"] = tip.threshold;
    c["initiation_time_s"] = tracker.initiation_time() ? nlohmann::json(*tracker.initiation_time())
                                                       : nlohmann::json(nullptr);
    c["branching_time_s"] = tracker.branching_time() ? nlohmann::json(*tracker.branching_time())
                                                     : nlohmann::json(nullptr);
    c["first_advance_time_s"] = tracker.first_advance_time()
                                    ? nlohmann::json(*tracker.first_advance_time())
                                    : nlohmann::json(nullptr);
    if (tracker.branching_point()) {
      c["branch_length_m"] = norm(sub(*tracker.branching_point(), tip.origin));
      c["branch_separation_time_s"] = *tracker.separation_time();
      c["branch_separation_length_m"] = norm(sub(*tracker.separation_point(), tip.origin));
      const std::optional<double> asym = tracker.mirror_asymmetry(ns);
      c["branch_asymmetry_m"] = asym ? nlohmann::json(*asym) : nlohmann::json(nullptr);
    }
    if (!tracker.path().empty()) {
      // Angle of the segment from the initial tip to the last tip, from the tracking direction
      // (counter-clockwise positive): the path angle of a straight crack.
      const Vec3 r = sub(tracker.path().back().position, tip.origin);
      const Vec3 nrm{-tip.direction[1], tip.direction[0], 0.0};
      if (norm(r) > tip.advance)
        c["path_angle_deg"] = std::atan2(dot(r, nrm), dot(r, tip.direction)) * 180.0 / M_PI;
    }
    c["mean_speed_m_s"] = tracker.mean_speed();
    c["max_speed_m_s"] = tracker.max_speed();
    c["speed_window_s"] = tip.window;
    nlohmann::json path = nlohmann::json::array();
    for (const TipSample& s : tracker.path())
      path.push_back({s.time, s.position[0], s.position[1], s.position[2]});
    c["tip_path"] = path;  // [t, x, y, z]
    if (!tracker.path().empty()) {
      const Vec3& last = tracker.path().back().position;
      c["final_tip_m"] = {last[0], last[1], last[2]};
      if (!dk.grid.holes.empty()) {
        // Crack-hole interaction (thesis 6.3): how close the tracked tip came to any hole.
        double closest = std::numeric_limits<double>::infinity();
        for (const TipSample& s : tracker.path())
          for (const Shape& h : dk.grid.holes) closest = std::min(closest, h.distance_to_shape(s.position));
        c["closest_approach_to_hole_m"] = closest;
      }
    }
    nlohmann::json sp = nlohmann::json::array();
    for (const auto& w : tracker.speeds()) sp.push_back({w[0], w[1]});
    c["speed_history"] = sp;  // [t_mid, v]
    j["crack"] = c;
    if (opt.write_files && !tracker.speeds().empty()) {
      // Tip speed over time (Eq. 6.1 windows) as CSV and a plot.
      PlotSeries ps{"tip speed (Eq. 6.1)", {}, {}};
      write_file_atomically(dir + "/crack_speed.csv", [&](std::ostream& sc) {
        sc << "time_s,tip_speed_m_s\n";
        for (const auto& w : tracker.speeds()) {
          sc << fmt::format("{:.9e},{:.6e}\n", w[0], w[1]);
          ps.x.push_back(w[0] * 1e6);
          ps.y.push_back(w[1]);
        }
      });
      PlotOptions po;
      po.title = "crack tip speed";
      po.x_label = "time (us)";
      po.y_label = "speed (m/s)";
      write_line_plot(dir + "/crack_speed.png", {ps}, po);
    }
  }
  if (opt.write_files && dk.output.load_displacement)
    write_load_displacement_png(dir, hist.text_so_far(), *dk.output.load_displacement, m);
  if (opt.write_files) {
    j["outputs"] = {{"pvd", vtu ? vtu->pvd_path() : ""},
                    {"history", dir + "/history.csv"},
                    {"png", pngs}};
    hist.finish();
    refinement_log.finish();
    write_file_atomically(dir + "/summary.json", [&](std::ostream& o) { o << j.dump(2) << "\n"; });
  }
  return res;
}

}  // namespace periadapt
