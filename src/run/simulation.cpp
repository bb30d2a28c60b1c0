#include "run/simulation.hpp"

#include "adapt/setup_zones.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "adapt/adaptor.hpp"
#include "adapt/setup_zones.hpp"
#include "core/binary_archive.hpp"
#include "input/deck_error.hpp"
#include "model/model_state.hpp"
#include "parallel/held_rows.hpp"
#include "parallel/mpi_env.hpp"
#include "run/checkpoint_file.hpp"
#include "run/checkpoint_pieces.hpp"
#include "run/crack_tip_observer.hpp"
#include "run/history_observer.hpp"
#include "run/interrupt.hpp"
#include "run/picture_observer.hpp"
#include "run/progress.hpp"
#include "run/refinement_log_observer.hpp"
#include "run/snapshot_observer.hpp"
#include "run/summary_observer.hpp"
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
    if ((starts("snapshot_") && ends(".vtu")) || is_damage_picture(name) ||
        name == kCheckpointName || is_checkpoint_piece(name) || name == "refinement.csv" ||
        name == "crack_speed.csv" || name == "crack_speed.png" || name == "load_displacement.png")
      fs::remove(e.path(), ec);
  }
}

// Whether the automatic profile's set-up zones (adapt/setup_zones.hpp) may refine before the run.
bool refines_at_setup(const Deck& dk) {
  const AdaptSpec& a = dk.adapt;
  if (!a.enabled || a.start_time > 0) return false;
  if (a.refine_crack_tips && !dk.cracks.empty()) return true;
  if (a.refine_motions)
    for (const MotionSpec& mo : dk.motions)
      for (const auto& c : mo.component)
        if (c && component_moves(mo.kind == MotionSpec::Kind::Velocity, Expression(*c))) return true;
  return false;
}

// A distributed explicit run whose ranks hold their own bond rows from the set-up on
// (parallel/held_rows.hpp): owned integration, and nothing that reads another rank's rows
// (the overlay, which re-checks a bond over both ends' families; of refinement, what
// Adaptor::rows_can_be_held names). A restart
// builds the same rows and reads their bonds from the checkpoint; an adaptive one, whose node
// set is the checkpoint's, splits the checkpoint's rows afresh and reads its own. Runs refined
// before they start hold their rows from their first pass on.
bool holds_rows_from_setup(const Deck& dk) {
  const AdaptSpec& a = dk.adapt;
  const bool events_allow = !a.enabled || (a.initial.empty() && !refines_at_setup(dk) && !a.coarsen &&
                                           a.relax_sweeps == 0 && !a.conserve_energy &&
                                           !a.interface_fit);
  // A surface correction is made at set-up from each row's owner; an event's correction window
  // reads rows around it.
  return mpi::distributed() && dk.owned_integration && events_allow && !a.ghost_correction &&
         !dk.pdro.enabled && (!a.enabled || dk.surface_correction == SurfaceCorrection::None);
}

}  // namespace

TimeStepChoice choose_time_step(const Deck& dk, const Model& m) {
  const StableStep s = stable_time_step(m);
  TimeStepChoice c{0, s.dt, s.node, 0, 1.0};
  if (dk.adapt.enabled && dk.solver == Deck::SolverType::Explicit) {
    // The stable step scales with the horizon (sum_j C_ij V_j ~ c delta^(dim-1) ~ 1/delta^2):
    // the finest level's bound applies from the first event on, so it is checked (and the
    // default step chosen) now rather than when the first refinement happens. Each node's bound
    // is scaled from its own horizon (after an initial refinement some are on a finer level).
    const NodeSet& ns = m.nodes;
    std::vector<double> finest(static_cast<std::size_t>(dk.adapt.max_level) + 1);
    for (int l = dk.adapt.max_level; l >= 0; --l)
      finest[l] = std::min(level_horizon(m, dk.adapt, l),
                           l < dk.adapt.max_level ? finest[l + 1] : INFINITY);
    std::vector<double> scale(ns.size(), 1.0);
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.horizon[i] > 0 && ns.level[i] <= dk.adapt.max_level)
        scale[i] = std::min(1.0, finest[static_cast<std::size_t>(ns.level[i])] / ns.horizon[i]);
    c.level_ratio = std::min(1.0, scaled_stable_time_step(m, scale).dt / s.dt);
  }
  if (dk.time_step) {
    if (*dk.time_step > s.dt && !dk.allow_unstable_time_step)
      throw DeckError(dk.file, dk.time_step_at,
                      fmt::format("{:.4g} s exceeds the stable time step {:.4g} s (Silling-Askari "
                                  "bound, limited by node {}); use a smaller value or set "
                                  "solver.allow_unstable_time_step: true",
                                  *dk.time_step, s.dt, s.node));
    if (*dk.time_step > s.dt * c.level_ratio * (1 + 1e-9) && !dk.allow_unstable_time_step)
      throw DeckError(dk.file, dk.time_step_at,
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


void enable_distributed_forces(const Deck& dk, Model& m) {
  m.partition.active = true;
  m.partition.method = dk.partition;
  m.partition.rebalance_threshold = dk.rebalance_threshold;
}

RunResult run_simulation(const Deck& dk, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  RunResult res;
  Model& m = res.model;
  if (holds_rows_from_setup(dk)) {
    const HeldReach reach =
        held_reach(Formulation::named(dk.formulation, false)->state_based(), dk.dual_horizon);
    m = build_model(dk, [&](const NodeSet& ns, const QuadratureSpec& q, RowPartition& p) {
      p.method = dk.partition;
      p.rebalance_threshold = dk.rebalance_threshold;
      return build_held_families(p, ns, q, reach);
    });
    share_held_setup(m.partition, m.nodes, m.bonds, m.precrack_bonds);
  } else {
    m = build_model(dk);
  }
  if (mpi::distributed()) {
    enable_distributed_forces(dk, m);
  }
  // Refinement events change the rows (a restart reads an adaptive run's rows by that).
  m.partition.refining = dk.adapt.enabled;
  const double t_setup = std::chrono::duration<double>(clock::now() - t_start).count();
  const TimeStepChoice ts = choose_time_step(dk, m);
  const NodeSet& ns = m.nodes;

  const std::string dir = opt.out_dir ? *opt.out_dir : dk.output.directory;
  if (opt.write_files) std::filesystem::create_directories(dir);
  // A restart reads its checkpoint before anything is written (a mismatch changes nothing).
  std::optional<Checkpoint> restart;
  std::optional<ArchiveReader> state;
  if (opt.restart) {
    restart = read_checkpoint(*opt.restart, dk);
    if (restart->info.step >= ts.steps)
      throw DeckError(dk.file, 0, 0, dk.steps ? "solver.steps" : "solver.end_time",
                      fmt::format("the run would end at step {} (t = {:.6e} s), not past its "
                                  "checkpoint's step {} (t = {:.6e} s): a restart continues a run, "
                                  "so give a later end",
                                  ts.steps, ts.steps * ts.dt, restart->info.step, restart->info.time));
    state.emplace(restart->payload, restart->path);
    std::optional<DeckError> failed;
    try {
      restore_model_state(*state, m, piece_reader(restart->path, dk));
    } catch (const ArchiveError& e) {
      failed.emplace(restart->path, 0, 0, "--restart", e.what());
    } catch (const DeckError& e) {
      failed.emplace(e);
    }
    // The ranks read different pieces: all stop, with the first error any met.
    const std::string error = mpi::first_text(failed ? failed->what() : "");
    if (!error.empty()) throw DeckError(DeckError::Formatted{}, error, "--restart");
    if (restart->info.threads != omp_get_max_threads() && !opt.quiet)
      fmt::print("note: the checkpoint was written with {} threads, this run has {}: it continues "
                 "correctly, but not bit for bit\n",
                 restart->info.threads, omp_get_max_threads());
  } else if (opt.write_files) {
    remove_earlier_run_outputs(dir);
  }
  // Rank 0 clears the folder before any rank writes its snapshot pieces into it.
  if (mpi::distributed()) mpi::max(0L);
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

  VelocityVerlet vv(m, ts.dt);
  if (dk.multirate) vv.set_multirate(dk.safety, dk.multirate_ratio);
  if (m.partition.active && dk.owned_integration) vv.enable_owned_integration();
  if (!restart) vv.initialize();
  std::unique_ptr<Adaptor> adaptor;
  if (dk.adapt.enabled) {
    adaptor = std::make_unique<Adaptor>(m, vv, dk.adapt);
  } else {
    // The energy trigger is the only reader of multi-rate's recent densities: without it no pass
    // writes them (and owned integration need not run the steps before a check whole).
    vv.keep_energies_for_checks(0);
  }
  // Each rank keeps the bond rows its own passes read; refinement events gather the rows they
  // read onto every rank first.
  // (Contact and impactors act between nodes: with them every rank integrates every node, from
  // every row's force, and still needs only its own rows' bonds.)
  m.partition.hold_rows = m.partition.active && dk.owned_integration && !dk.pdro.enabled &&
                          !m.ghost.enabled && (!adaptor || adaptor->rows_can_be_held());
  if (m.partition.rows_held && adaptor && !adaptor->rows_can_be_held())
    throw std::logic_error("held bond rows in a run whose events read other ranks' rows");

  RunView view(dk, m, vv, adaptor.get(), dir, opt.write_files, ts.steps, t_start);
  // Observers, in the order they see each step: the tip before the history row that shows it;
  // the summary last, as it writes what the others filled in.
  std::vector<std::shared_ptr<RunObserver>> observers;
  const CrackTipObserver* tip = nullptr;
  if (dk.output.track_tip && ns.dim >= 2) {
    auto t = std::make_shared<CrackTipObserver>(view);
    tip = t.get();
    observers.push_back(std::move(t));
  }
  observers.push_back(std::make_shared<HistoryObserver>(view, tip));
  observers.push_back(std::make_shared<SnapshotObserver>(view));
  observers.push_back(std::make_shared<PictureObserver>(view, ts.dt));
  if (adaptor) observers.push_back(std::make_shared<RefinementLogObserver>(view));
  for (const auto& o : opt.observers) observers.push_back(o);
  observers.push_back(std::make_shared<SummaryObserver>(view));

  RunTotals& tot = view.totals;
  tot.setup_s = t_setup;
  tot.dt = ts.dt;
  tot.dt_stable = ts.dt_crit;
  auto observe = [&](long step, bool closing) {
    const auto t0 = clock::now();
    for (auto& o : observers) o->on_step(view, step, closing);
    tot.sampling_s += std::chrono::duration<double>(clock::now() - t0).count();
  };
  std::size_t events_seen = 0;
  auto report_events = [&]() {
    if (!adaptor) return;
    const auto& evs = adaptor->events();
    for (; events_seen < evs.size(); ++events_seen)
      for (auto& o : observers) o->on_event(view, evs[events_seen]);
  };

  // Checkpoints: the state after a step and its scheduled outputs; the run's own files so far
  // travel inside, so a restart rewrites them as they were at that step.
  // Held bond rows travel in pieces, one per rank, beside it.
  const bool writes_files = mpi::max(static_cast<long>(opt.write_files)) != 0;
  auto write_run_checkpoint = [&]() {
    CheckpointInfo info{build_id(), deck_fingerprint(dk), dk.file, omp_get_max_threads(),
                        vv.step_count(), vv.time()};
    BondPieces pieces;
    if (m.partition.rows_held) pieces = write_bond_pieces(dir, info, m);
    if (!opt.write_files) return;
    ArchiveWriter w;
    save_model_state(w, m, &pieces);
    vv.save_state(w);
    w.put<std::uint8_t>(adaptor != nullptr);
    if (adaptor) adaptor->save_state(w);
    w.tag("OUTS");
    w.put(std::uint64_t{events_seen});
    for (auto& o : observers) o->save(w);
    w.put(tot.solver_s);
    w.put(tot.sampling_s);
    w.put(view.output_seconds);
    write_checkpoint(dir + "/" + kCheckpointName, info, w.take());
    remove_stale_pieces(dir, pieces);
  };
  auto restore_run_state = [&](ArchiveReader& r) {
    vv.restore_state(r);
    if (r.get<std::uint8_t>() != (adaptor != nullptr))
      throw ArchiveError("the checkpoint and the deck differ in adapt");
    if (adaptor) adaptor->restore_state(r);
    r.tag("OUTS");
    events_seen = r.get<std::uint64_t>();
    for (auto& o : observers) o->restore(r, view);
    r.get(tot.solver_s);
    r.get(tot.sampling_s);
    r.get(view.output_seconds);
    if (!r.at_end()) throw ArchiveError("the checkpoint has data past its last section");
  };

  if (restart) {
    try {
      restore_run_state(*state);
    } catch (const ArchiveError& e) {
      throw DeckError(restart->path, 0, 0, "--restart", e.what());
    }
    state.reset();
    std::string().swap(restart->payload);  // restored: the run does not keep the file's bytes
    tot.restarted = true;
    tot.restarted_from_step = vv.step_count();
    if (!opt.quiet)
      fmt::print("restarted from {} at step {} (t = {:.6e} s)\n", restart->path, vv.step_count(),
                 vv.time());
  } else {
    for (auto& o : observers) o->on_start(view);
    observe(0, false);
  }
  const long first_step = vv.step_count() + 1;
  Progress bar(ts.steps, opt.quiet);
  for (long s = first_step; s <= ts.steps; ++s) {
    const auto t0 = clock::now();
    bool energy = false, every_row = false;
    for (const auto& o : observers)
      if (o->wants_energy_density(s)) {
        energy = true;
        every_row = every_row || !o->own_rows_suffice();
      }
    if (energy) vv.request_energy_at(s, every_row);
    bool ok = false;
    try {
      ok = adaptor ? adaptor->step() : vv.step();
    } catch (const UnstableAfterRefinement& e) {
      res.unstable_time_step = e.what();
    }
    tot.solver_s += std::chrono::duration<double>(clock::now() - t0).count();
    report_events();
    if (res.unstable_time_step) {
      // The state is sound; only the next step would not be: its outputs are kept.
      observe(s, true);
      res.steps_done = s;
      break;
    }
    if (!ok) {
      res.diverged = true;
      break;
    }
    // A signal reaches the ranks at different moments: all stop at the first step any saw it.
    res.interrupted = static_cast<int>(mpi::max(interrupt_signal()));
    const bool checkpoint = res.interrupted || (dk.output.checkpoint_every > 0 &&
                                                s % dk.output.checkpoint_every == 0 && s < ts.steps);
    if (vv.owned_integration()) {
      // The ranks agree (an observer may act on rank 0 alone).
      bool wanted = checkpoint || s == ts.steps;
      for (const auto& o : observers) wanted = wanted || o->wants_state(view, s);
      if (mpi::max(wanted)) vv.sync_state();
    }
    observe(s, false);
    if (checkpoint && writes_files) write_run_checkpoint();
    if (res.interrupted) observe(s, true);
    std::string note;
    for (const auto& o : observers)
      if (note.empty()) note = o->progress_note();
    bar.update(s, note);
    if (res.interrupted) {
      res.steps_done = s;
      break;
    }
  }
  bar.finish();
  vv.sync_state();  // the outputs and the returned model read every node

  tot.wall_s = std::chrono::duration<double>(clock::now() - t_start).count();
  tot.status = res.diverged             ? "diverged"
               : res.unstable_time_step ? "unstable_time_step"
               : res.interrupted        ? "interrupted"
                                        : "completed";
  tot.interrupted_by = res.interrupted;
  tot.steps_done = res.steps_done;
  for (auto& o : observers) o->finish(view, res);
  return res;
}

}  // namespace periadapt
