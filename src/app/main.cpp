// periadapt: command-line entry (run, check).
#include <algorithm>
#include <omp.h>

#include <filesystem>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <iostream>

#include <fmt/format.h>

#include "parallel/mpi_env.hpp"

#include "run/refinement_forecast.hpp"
#include "run/simulation.hpp"
#include "run/sweep.hpp"
#include "run/static_run.hpp"
#include "run/relaxation_run.hpp"
#include "adapt/refine.hpp"
#include "adapt/setup_zones.hpp"
#include "discretize/lattice_moment.hpp"
#include "studies/registry.hpp"
#include "input/deck.hpp"
#include "run/interrupt.hpp"
#include "io/atomic_output.hpp"
#include "input/deck_error.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"

using namespace periadapt;

namespace {

// The --set options of a run, quoted for a shell, to restate in the command that continues it.
std::string restart_settings(const std::vector<std::string>& overrides) {
  std::string out;
  for (const std::string& o : overrides) {
    std::string q;
    for (char c : o) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += " --set '" + q + "'";
  }
  return out;
}

int check(const std::string& path, const std::vector<std::string>& overrides,
          const std::string& nodes_csv) {
  const Deck dk = load_deck(path, overrides);
  if (dk.solver == Deck::SolverType::Static) require_held_displacements(dk);
  const Model m = build_model(dk);
  if (!nodes_csv.empty()) {
    // The discretization as a point cloud (discretization.body.points), shortest round-trip
    // decimals so that reading it back gives the same doubles.
    write_file_atomically(nodes_csv, [&](std::ostream& out) {
      const NodeSet& ns = m.nodes;
      out << (ns.dim == 1 ? "x,volume\n" : ns.dim == 2 ? "x,y,volume\n" : "x,y,z,volume\n");
      for (std::size_t i = 0; i < ns.size(); ++i) {
        if (!(ns.flags[i] & kActive)) continue;
        for (int d = 0; d < ns.dim; ++d) out << fmt::format("{},", ns.x[d][i]);
        out << fmt::format("{}\n", ns.volume[i]);
      }
    });
    fmt::print("nodes written   {}\n", nodes_csv);
  }
  const bool is_static = dk.solver != Deck::SolverType::Explicit;
  const TimeStepChoice ts = is_static ? TimeStepChoice{0, 0, 0, 0} : choose_time_step(dk, m);
  const MaterialLaw& mat = m.material;
  fmt::print("deck            {}\n", path);
  fmt::print("model           {}D {}{}\n", dk.dim,
             m.formulation.state_based() ? "LPS (state-based)"
             : m.formulation.keeps_bond_history()
                 ? m.formulation.label() + " (bond-based, PMB elastic branch)"
                 : std::string("PMB"),
             dk.dim == 2 ? (dk.plane == PlaneCondition::Stress ? ", plane stress" : ", plane strain") : "");
  if (dk.dim < 3) fmt::print("thickness/area  {:.6g}\n", dk.thickness);
  fmt::print("material        {}: E = {:.6g} Pa, rho = {:.6g} kg/m^3, nu = {:.6g}{}\n",
             mat.name, mat.E, mat.rho, mat.nu, m.formulation.bond_based() ? " (fixed by PMB)" : "");
  fmt::print("micromodulus    {} shape, c0 = {:.6e}{}\n", to_string(mat.shape), mat.c0,
             mat.lattice_calibration
                 ? fmt::format(" (nodes: x {:.5f}, lattice calibration)", m.nodes.micromodulus[0] / mat.c0)
                 : std::string());
  if (mat.G0 > 0) fmt::print("fracture energy G0 = {:.6g} J/m^2\n", mat.G0);
  if (m.formulation.keeps_bond_history())
    fmt::print("{}    {:.6g} Pa: onset stretch {:.6e}\n", m.formulation.law->stress_key, dk.law_stress,
               mat.onset_stretch);
  fmt::print("{} s0 = {:.6e}{}\n", m.formulation.keeps_bond_history() ? "breaking stretch" : "critical stretch", mat.s0,
             dk.damage ? "" : " (damage disabled)");
  for (std::size_t b = 1; b < m.block_materials.size(); ++b) {
    const MaterialLaw& l = m.block_materials[b];
    fmt::print("block           {}: E = {:.6g} Pa, rho = {:.6g} kg/m^3, nu = {:.6g}, {}s0 = {:.6e}, "
               "{} nodes\n",
               l.name, l.E, l.rho, l.nu, l.G0 > 0 ? fmt::format("G0 = {:.6g} J/m^2, ", l.G0) : "",
               l.s0, std::count(m.nodes.block.begin(), m.nodes.block.end(), b));
  }
  fmt::print("grid            spacing {:.6g} m, horizon {:.6g} m (m = {:.4g}), rotation {:.6g} deg, "
             "quadrature {}\n",
             dk.grid.spacing, dk.horizon, dk.horizon_factor, dk.grid.rotation_deg,
             dk.quadrature == Quadrature::Full ? "full" : dk.quadrature == Quadrature::Subcell ? "subcell" : dk.quadrature == Quadrature::IpaHybrid ? "ipa_hybrid" : "pa_pdlammps");
  fmt::print("nodes           {}\n", m.nodes.size());
  fmt::print("bonds           {} (mean {:.1f} per node), {} cut by {} pre-crack(s)\n",
             m.bonds.num_bonds(),
             static_cast<double>(m.bonds.num_bonds()) / static_cast<double>(m.nodes.size()),
             m.precrack_bonds, dk.cracks.size());
  fmt::print("wave speed      {:.6g} m/s\n", mat.wave_speed);
  if (is_static) {
    if (dk.solver == Deck::SolverType::Static)
      fmt::print("solver          static (linearized bond-based, {} bond pairing)\n",
                 dk.dual_horizon ? "dual-horizon" : "source-horizon");
    else
      fmt::print("solver          dynamic relaxation, {} load steps, tolerance {:.3g}\n",
                 dk.load_steps, dk.relax_tolerance);
  } else {
    fmt::print("dt_crit         {:.6e} s (Silling-Askari, node {})\n", ts.dt_crit, ts.limiting_node);
    fmt::print("dt              {:.6e} s{}\n", ts.dt,
               dk.time_step            ? " (deck)"
               : ts.level_ratio < 1.0 ? fmt::format(" (safety x dt_crit x {:.4g}, the finest level's bound)", ts.level_ratio)
                                       : std::string(" (safety x dt_crit)"));
    fmt::print("steps           {} (end time {:.6e} s)\n", ts.steps, ts.steps * ts.dt);
    if (dk.multirate) {
      fmt::print("multi-rate      nodes whose stable step is at least k dt / {:.3g} take k dt, "
                 "k <= {} (solver.multirate)\n",
                 dk.safety, dk.multirate_ratio);
      // The rates of the initial grid, from the solver itself (on a copy: it writes forces).
      Model probe = m;
      VelocityVerlet vv(probe, ts.dt);
      vv.set_multirate(dk.safety, dk.multirate_ratio);
      vv.initialize();
      std::vector<std::size_t> count(static_cast<std::size_t>(dk.multirate_ratio) + 1, 0);
      for (std::size_t i = 0; i < probe.nodes.size(); ++i)
        if (probe.nodes.flags[i] & kActive) ++count[vv.rates()[i]];
      std::string line;
      for (int k = 1; k <= dk.multirate_ratio; ++k)
        line += fmt::format("{}{} nodes on {} dt", k > 1 ? ", " : "", count[static_cast<std::size_t>(k)], k);
      fmt::print("  at t = 0      {}\n", line);
    }
  }
  for (const BodyLoad& l : m.loads)
    fmt::print("load            {}: {} nodes, body force density [{:.4g}, {:.4g}, {:.4g}] N/m^3\n",
               l.name, l.nodes.size(), l.density[0], l.density[1], l.density[2]);
  for (const PrescribedMotion& p : m.motions)
    fmt::print("motion          {}: {} nodes ({})\n", p.name, p.nodes.size(),
               p.kind == PrescribedMotion::Kind::Velocity ? "velocity" : "displacement");
  std::size_t nofail = 0;
  for (auto f : m.nodes.flags) nofail += (f & kNoFail) != 0;
  fmt::print("no-fail nodes   {}\n", nofail);
  const std::size_t per_node = model_bytes_per_node(m);
  fmt::print("memory          {:.1f} MB bonds ({} B/bond), {:.1f} MB nodes ({} B/node incl. row "
             "index{})\n",
             static_cast<double>(m.bonds.bond_array_bytes()) / 1e6, BondFamilies::bytes_per_bond(),
             static_cast<double>(m.nodes.size() * per_node) / 1e6, per_node,
             m.loads.empty() ? "" : " and body forces");
  if (dk.adapt.enabled) {
    const AdaptSpec& a = dk.adapt;
    std::string trig;
    if (a.stretch_fraction)
      trig += fmt::format("bond stretch >= {:.3g} x the children's critical stretch{}",
                          *a.stretch_fraction,
                          a.stretch_reach > 0
                              ? fmt::format(" (once cracked, within {:.3g} horizons of a crack)",
                                            a.stretch_reach)
                              : std::string());
    if (a.energy_fraction)
      trig += std::string(trig.empty() ? "" : " and ") +
              fmt::format("energy W >= {:.3g} W_max", *a.energy_fraction);
    if (a.damage_trigger) trig += std::string(trig.empty() ? "" : " and ") + "damage growth";
    // The set-up zones this deck has (the model was built with them).
    std::string setup;
    const std::size_t fronts = a.refine_crack_tips && a.start_time <= 0 ? crack_tip_zones(m, a.max_level).size() : 0;
    const std::size_t patches = a.refine_motions && a.start_time <= 0 ? driven_patch_zones(m, a.max_level).size() : 0;
    if (fronts + patches > 0)
      setup = fmt::format(", refined at set-up: {} pre-crack front points, {} driven regions", fronts, patches);
    fmt::print("adapt           method {} to level {}, {}-scaling, {}, from t = {:.4g} s{}{}\n",
               a.method == NodeGeneration::A ? "A" : "B", a.max_level,
               a.scaling == HorizonScaling::Delta ? "delta" : a.scaling == HorizonScaling::M ? "m" : "delta-m",
               trig, a.start_time, a.interface_horizon ? ", interface-horizon correction" : "", setup);
    // The quadrature's bulk bond stiffness at each level's m: levels that differ in it meet with
    // an impedance jump (a wave reflects) unless the micromoduli are calibrated to it.
    auto stiffness = [&](int l) {
      return lattice_bond_moment(dk.quadrature, dk.dim, dk.shape,
                                 level_horizon(m, a, l) / (m.grid_spacing / std::ldexp(1.0, l)));
    };
    double lo = stiffness(0), hi = lo;
    for (int l = 1; l <= a.max_level; ++l) {
      const double k = stiffness(l);
      lo = std::min(lo, k), hi = std::max(hi, k);
      fmt::print("  level {}       spacing {:.6g} m, horizon {:.6g} m, quadrature bond stiffness {:.4f}{}\n", l,
                 m.grid_spacing / std::ldexp(1.0, l), level_horizon(m, a, l), k,
                 m.formulation.bond_based() ? "" : " (LPS normalizes by it)");
    }
    if (m.formulation.bond_based() && !mat.lattice_calibration && hi > 1.01 * lo)
      fmt::print("note            the levels' quadrature bond stiffness differs by {:.1f}% (level 0: "
                 "{:.4f}): waves reflect at level interfaces; discretization.micromodulus_calibration: "
                 "lattice matches them\n", 100 * (hi / lo - 1), stiffness(0));
  }
  if (dk.adapt.enabled || !dk.adapt.initial.empty()) {
    // What the initial zones refined already (model built with them): nodes and body volume.
    std::size_t active = 0, refined = 0;
    double vol = 0, vol_refined = 0;
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
      if (!(m.nodes.flags[i] & kActive)) continue;
      ++active;
      vol += m.nodes.volume[i];
      if (m.nodes.level[i] > 0) ++refined, vol_refined += m.nodes.volume[i];
    }
    fmt::print("initial zones   {} of {} active nodes refined, {:.1f}% of the body's volume\n",
               refined, active, vol > 0 ? 100.0 * vol_refined / vol : 0.0);
    if (vol > 0 && vol_refined > 0.5 * vol)
      fmt::print("warning         the initial zones refine more than half of the body: a uniform "
                 "grid of the finer spacing may cost less\n");
  }
  if (dk.adapt.enabled && dk.adapt.stretch_fraction) {
    // About 10 s of this machine's time at most (plain PMB runs 1e8-5e8 bonds per second).
    constexpr double kForecastBudget = 2e9;
    const RefinementForecast fc = forecast_refinement(dk, kForecastBudget);
    if (!fc.ran) {
      fmt::print("forecast        skipped: the elastic coarse run would take {:.2g} bond "
                 "evaluations (more than {:.0e})\n", fc.bond_evaluations, kForecastBudget);
    } else {
      fmt::print("forecast        elastic coarse run: {} at t = {:.4g} s; by then the stretch "
                 "trigger would have refined {} of {} refinable nodes, {:.1f}% of the body's "
                 "volume\n",
                 fc.initiates ? "the first bond reaches its children's s0"
                              : "no bond reaches its children's s0 up to end_time",
                 fc.time, fc.parents, fc.refinable, 100 * fc.volume_fraction);
      if (fc.volume_fraction > 0.5)
        fmt::print("warning         the run is likely to refine most of the body before a crack "
                   "starts: a uniform grid of the finer spacing may cost less, or give "
                   "adapt.region\n");
    }
  }
  fmt::print("output          {}\n", dk.output.directory);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun every rank runs the same run on the same data (parallel/row_partition.hpp);
  // rank 0 alone prints and writes files.
  const mpi::Session mpi_session(argc, argv);
  if (mpi::rank() > 0) {
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
      return 1;
  }
  CLI::App app{"PeriAdapt: peridynamics with adaptive grid refinement and scaling"};
  app.set_version_flag("--version", std::string("periadapt ") + PERIADAPT_VERSION +
                                        (mpi::built_with_mpi() ? " (MPI: yes)" : " (MPI: no)"));
  app.require_subcommand(1);
  std::string deck, out;
  int threads = 0;
  bool quiet = false;
  CLI::App* run = app.add_subcommand("run", "run a deck");
  run->add_option("deck", deck, "YAML input deck")->required();
  run->add_option("--out", out, "output directory (overrides output.directory)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  run->add_flag("--quiet", quiet, "no progress output");
  std::vector<std::string> overrides;
  std::string restart_from;
  run->add_option("--restart", restart_from,
                  "continue from a checkpoint (a checkpoint.bin, or the output folder holding it)");
  run->add_option("--set", overrides,
                  "override a deck key, checked like the deck's own: key.path=value (repeatable; "
                  "a number indexes a list, e.g. loads.0.value=[0,2e7])");
  CLI::App* chk = app.add_subcommand("check", "validate a deck and print every resolved parameter");
  chk->add_option("deck", deck, "YAML input deck")->required();
  chk->add_option("--set", overrides, "override a deck key: key.path=value (repeatable)");
  std::string nodes_csv;
  chk->add_option("--write-nodes", nodes_csv,
                  "also write the nodes as a point cloud (x,y,z,volume CSV) that "
                  "discretization.body.points reads back");
  std::vector<std::string> sweep_sets;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "run a deck for every combination of key values, each run in OUT/run_NNNN, "
               "results in OUT/sweep.csv");
  sweep->add_option("deck", deck, "YAML input deck")->required();
  sweep->add_option("--set", sweep_sets,
                    "key.path=v1,v2,... (repeatable; every combination runs; commas inside [] or "
                    "{} belong to one value)")
      ->required();
  sweep->add_option("--out", out, "folder of the sweep (default: the deck's output.directory)");
  sweep->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  sweep->add_flag("--quiet", quiet, "no progress output");
  std::string study_name;
  CLI::App* study = app.add_subcommand("study", "run a built-in study of the seeds and print its "
                                                "tables beside the published numbers");
  std::vector<std::string> study_names;
  std::string study_help = "study name:";
  for (const Study& st : studies()) {
    study_names.push_back(st.name);
    study_help += fmt::format("\n    {:22s}{}", st.name, st.what);
  }
  study->add_option("name", study_name, study_help)->required()->check(CLI::IsMember(study_names));
  StudyOptions study_opt;
  study->add_option("--out", out, "directory for the study's CSV files");
  study->add_flag("--pim", study_opt.pim, "pdro-*: overlay interpolation by PIM instead of PDDO");
  study->add_flag("--gaussian", study_opt.gaussian,
                  "pdro-*: PDDO with the Gaussian weight exp(-4 r^2/delta^2) instead of uniform");
  study->add_flag("--whole-bond", study_opt.whole_bond,
                  "pdro-*: overlay sub-pairs over the whole bond instead of the paper's three");
  study->add_option("--deck", study_opt.deck, "pdro-sent, pdro-disk: the deck to vary (default: "
                                              "examples/pdro_sent_2d.yaml, examples/pdro_disk_2d.yaml)");
  study->add_flag("--quick", study_opt.quick, "pdro-bar: targets 0.9, 0.5, 0.2 mm only; pdro-sent: 1 mm native and n = 2, 5 only; pdro-disk: n = 2 only; bobaru-1d-density-jump: Table III grids only");
  study->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  // A first word that is no subcommand (CLI11 would report only that one is required).
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->get_name() == word;
    if (!known) {
      fmt::print(stderr, "error: '{}' is not a periadapt command; the commands are run, check, "
                         "sweep and study (periadapt --help)\n", word);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (threads > 0) omp_set_num_threads(threads);
  std::string run_dir;
  if (mpi::distributed() && !run->parsed()) {
    if (mpi::rank() > 0) return 0;
    mpi::continue_alone();
    fmt::print(stderr, "note: only `run` is distributed; rank 0 does this alone\n");
  }
  try {
    if (chk->parsed()) return check(deck, overrides, nodes_csv);
    if (sweep->parsed()) {
      run_dir = out.empty() ? load_deck(deck).output.directory : out;
      return run_sweep(deck, sweep_sets, {}, run_dir, quiet);
    }
    if (run->get_option("--restart")->count() > 0 && restart_from.empty())
      throw DeckError(deck, 0, 0, "--restart",
                      "is empty: name a checkpoint.bin or the output folder holding it (an "
                      "empty value would start the run over and replace its checkpoint)");
    for (CLI::App* sub : {run, sweep, study})
      if (sub->parsed() && sub->get_option("--out")->count() > 0 && out.empty())
        throw DeckError(deck.empty() ? std::string("command line") : deck, 0, 0, "--out",
                        "is empty: name a folder (for the current one: '.')");
    if (study->parsed()) {
      if (!out.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(out, ec);
        if (ec) throw OutputError("cannot create the output folder " + out + ": " + ec.message());
      }
      study_opt.out_dir = out;
      return find_study(study_name)->run(study_opt);
    }
    RunOptions ro;
    if (!out.empty()) ro.out_dir = out;
    ro.quiet = quiet || mpi::rank() > 0;
    ro.write_files = mpi::rank() == 0;
    if (!restart_from.empty()) ro.restart = restart_from;
    const Deck dk = load_deck(deck, overrides);
    // One run per output folder at a time; the lock goes with the process.
    run_dir = ro.out_dir ? *ro.out_dir : dk.output.directory;
    std::optional<OutputFolderLock> lock;
    if (ro.write_files) {
      std::error_code ec;
      std::filesystem::create_directories(run_dir, ec);
      if (ec) throw OutputError("cannot create the output folder " + run_dir + ": " + ec.message());
      lock.emplace(run_dir);
    } else {
      run_dir.clear();  // no summary written on failure either
    }
    if (ro.restart && dk.solver != Deck::SolverType::Explicit)
      throw DeckError(deck, 0, 0, "--restart",
                      "restarts are for explicit runs; static and relaxation runs start over");
    if (dk.solver == Deck::SolverType::Relaxation) {
      install_interrupt_handlers();
      const RunResult r = run_relaxation(dk, ro);
      if (r.interrupted) {
        fmt::print(stderr,
                   "interrupted by signal {} after load step {} of {}: history, snapshots and "
                   "summary.json (status interrupted) up to that step are in {}\n",
                   r.interrupted, r.steps_done, dk.load_steps, run_dir);
        return 128 + r.interrupted;
      }
      fmt::print("done: dynamic relaxation, {} load steps, {} iterations, {} bonds broken\n",
                 dk.load_steps, r.summary["solver"]["iterations"].get<long>(),
                 r.summary["broken_bonds"].get<std::size_t>());
      return 0;
    }
    if (dk.solver == Deck::SolverType::Static) {
      const RunResult r = run_static(dk, ro);
      fmt::print("done: static solve, max |u| = {:.6e} m; outputs in {}\n",
                 r.summary["max_abs_displacement_m"].get<double>(),
                 ro.out_dir ? *ro.out_dir : dk.output.directory);
      return 0;
    }
    install_interrupt_handlers();
    RunResult r = run_simulation(dk, ro);
    if (r.interrupted) {
      fmt::print(stderr,
                 "interrupted by signal {} after step {}: history, snapshots so far, "
                 "summary.json (status interrupted) and checkpoint.bin are in {}; continue with "
                 "periadapt run {} --restart {} --out {}{}\n",
                 r.interrupted, r.steps_done, run_dir, deck, run_dir, run_dir,
                 restart_settings(overrides));
      return 128 + r.interrupted;
    }
    if (r.unstable_time_step) {
      fmt::print(stderr, "error: {}. The outputs up to step {} are kept in {} (summary.json "
                         "status unstable_time_step).\n",
                 *r.unstable_time_step, r.steps_done, run_dir);
      return 3;
    }
    if (r.divergence) {
      const DivergenceReport& d = *r.divergence;
      fmt::print(stderr,
                 "error: the simulation diverged at step {} (t = {:.4e} s): {} at node {} "
                 "(x = [{},{},{}]). Outputs up to the last good snapshot are kept in {}. Lower "
                 "solver.time_step or check loads and boundary conditions.\n",
                 d.step, d.time, d.reason, d.node, d.position[0], d.position[1], d.position[2],
                 ro.out_dir ? *ro.out_dir : dk.output.directory);
      return 3;
    }
    fmt::print("done: {} steps in {:.2f} s wall ({:.3g} bond evaluations/s{})\n", r.steps,
               r.wall_s, r.bond_evals_per_s,
               r.multirate_slow_nodes
                   ? fmt::format("; {} nodes on a longer step than dt at the end",
                                 *r.multirate_slow_nodes)
                   : std::string());
    if (r.crack) {
      auto us = [](const std::optional<double>& v) {
        return v ? fmt::format("{:.2f} us", *v * 1e6) : std::string("-");
      };
      fmt::print("crack: starts {} (initiation {}), branching {}, mean speed {:.0f} m/s, max speed "
                 "{:.0f} m/s\n",
                 us(r.crack->first_advance_s), us(r.crack->initiation_s),
                 us(r.crack->branching_s), r.crack->mean_speed, r.crack->max_speed);
    }
    if (!r.history_path.empty())
      fmt::print("outputs: {}{} , summary.json\n", r.pvd_path.empty() ? "" : r.pvd_path + " , ",
                 r.history_path);
    return 0;
  } catch (const DeckError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const OutputError& e) {
    // The files written before stay as they were; the summary says why the run stopped, if it
    // can still be written.
    fmt::print(stderr, "error: {}; the run stopped, earlier outputs are left as they were\n",
               e.what());
    if (!run_dir.empty()) {
      try {
        const nlohmann::json j = {{"status", "output_failed"}, {"error", e.what()}};
        write_file_atomically(run_dir + "/summary.json",
                              [&](std::ostream& o) { o << j.dump(2) << "\n"; });
      } catch (const OutputError&) {
      }
    }
    // Rank 0 alone writes files: the other ranks would wait for it in the next exchange.
    if (mpi::distributed()) mpi::abort(4);
    return 4;
  } catch (const std::filesystem::filesystem_error& e) {
    // A folder or file the run needed could not be made (a study's or a sweep's runs).
    fmt::print(stderr, "error: cannot write {}: {}\n", e.path1().string(), e.code().message());
    if (mpi::distributed()) mpi::abort(4);
    return 4;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    if (mpi::distributed()) mpi::abort(1);
    return 1;
  }
}
