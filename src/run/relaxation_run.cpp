#include "run/relaxation_run.hpp"

#include "io/atomic_output.hpp"

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>

#include "analysis/energy.hpp"
#include "run/resultants.hpp"
#include "run/output_regions.hpp"
#include "run/snapshot_fields.hpp"
#include "run/summary_observer.hpp"
#include "input/deck_error.hpp"
#include "io/vtu_writer.hpp"
#include "parallel/mpi_env.hpp"
#include "run/interrupt.hpp"
#include "setup/build_model.hpp"
#include "solver/dynamic_relaxation.hpp"

namespace periadapt {

RunResult run_relaxation(const Deck& dk, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  RunResult res;
  Model& m = res.model;
  m = build_model(dk);
  // Every rank relaxes the whole model alike; the force passes are split.
  if (mpi::distributed()) enable_distributed_forces(dk, m);
  const NodeSet& ns = m.nodes;
  const std::string dir = opt.out_dir ? *opt.out_dir : dk.output.directory;
  std::unique_ptr<VtuSeries> vtu;
  StreamedOutput hist;
  if (opt.write_files) {
    std::filesystem::create_directories(dir);
    if (dk.output.vtu) vtu = std::make_unique<VtuSeries>(dir, "snapshot", dk.output.vtu_zlib);
    hist = StreamedOutput(dir + "/history.csv");
    hist << "load_step,load_factor,iterations,relative_residual,newly_broken,broken_bonds,"
            "max_abs_displacement_m,strain_energy_J," + resultant_header(m) +
                region_header(dk.output.regions, ns.dim) + "wall_time_s\n";
  }
  RelaxationOptions ro;
  ro.load_steps = dk.load_steps;
  ro.tolerance = dk.relax_tolerance;
  ro.max_iterations = dk.relax_max_iterations;
  // The ranks agree on a signal (each relaxes the whole model; the force passes are shared).
  ro.stop_requested = [] { return mpi::max(interrupt_signal()) != 0; };
  std::size_t broken = 0;
  long iterations = 0;
  std::vector<double> W;
  RelaxationStepReport last;
  // ns.f holds the internal forces of the relaxed state when a load step ends.
  auto applied = [&](const BodyLoad& l) { return load_force(ns, l, l.amplitude(1e300) * last.load_factor); };
  auto reaction = [&](const PrescribedMotion& p) {
    return equilibrium_reaction(m, p, ns.f, last.load_factor);
  };
  int converged_steps = 0;
  const RelaxationStatus status = run_dynamic_relaxation(m, ro, [&](const RelaxationStepReport& r) {
    if (r.converged) converged_steps = r.load_step;
    last = r;
    broken += r.newly_broken;
    iterations += r.iterations;
    double umax = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (int d = 0; d < ns.dim; ++d) umax = std::max(umax, std::abs(ns.u[d][i]));
    const double U = strain_energy(m, W);
    if (hist.is_open())
      hist << fmt::format("{},{:.6g},{},{:.3e},{},{},{:.9e},{:.9e},{}{}{:.3f}\n", r.load_step,
                          r.load_factor, r.iterations, r.residual, r.newly_broken, broken, umax, U,
                          resultant_columns(m, applied, reaction),
                          region_columns(dk.output.regions, ns, W, ns.f),
                          std::chrono::duration<double>(clock::now() - t_start).count());
    if (vtu) vtu->write(r.load_factor, ns, snapshot_fields(m, W, dk.output.stress));
    if (!opt.quiet)
      fmt::print("load step {}/{} (factor {:.4g}): {} iterations, residual {:.2e}, {} bonds broke\n",
                 r.load_step, dk.load_steps, r.load_factor, r.iterations, r.residual,
                 r.newly_broken);
  });
  const bool ok = status == RelaxationStatus::Converged;
  if (status == RelaxationStatus::Interrupted) {
    res.interrupted = static_cast<int>(mpi::max(interrupt_signal()));
    res.steps_done = converged_steps;
  }
  nlohmann::json& j = res.summary;
  j["deck"] = dk.file;
  j["status"] = ok ? "completed" : res.interrupted ? "interrupted" : "not_converged";
  j["load_steps_converged"] = converged_steps;
  j["solver"] = {{"type", "relaxation"},
                 {"load_steps", dk.load_steps},
                 {"tolerance", dk.relax_tolerance},
                 {"iterations", iterations},
                 {"last_relative_residual", last.residual}};
  j["nodes"] = {{"initial", ns.size()}, {"final", ns.size()}};
  j["bonds"] = m.bonds.num_bonds();
  j["broken_bonds"] = broken;
  if (m.partition.active) j["ranks"] = ranks_json(m.partition);
  j["resultants"] = resultants_json(m, applied, reaction);
  if (!dk.output.regions.empty()) {
    strain_energy(m, W);
    j["regions"] = regions_json(dk.output.regions, ns, W, ns.f);
  }
  j["wall_time_s"] = std::chrono::duration<double>(clock::now() - t_start).count();
  if (opt.write_files) {
    if (dk.output.load_displacement)
      write_load_displacement_png(
          dir, hist.text_so_far(), *dk.output.load_displacement, m,
          !dk.initial_displacement[0] && !dk.initial_displacement[1] && !dk.initial_displacement[2]);
    hist.finish();
    write_file_atomically(dir + "/summary.json", [&](std::ostream& o) { o << j.dump(2) << "\n"; });
  }
  if (!ok && !res.interrupted)
    throw DeckError(dk.file, 0, 0, "solver.max_iterations",
                    fmt::format("dynamic relaxation did not converge at load step {} (relative "
                                "residual {:.3e} after {} iterations); raise max_iterations, use "
                                "more load_steps or a looser tolerance. Outputs up to the last "
                                "converged step are kept.",
                                last.load_step, last.residual, last.iterations));
  return res;
}

}  // namespace periadapt
