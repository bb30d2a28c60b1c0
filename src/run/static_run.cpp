#include "run/static_run.hpp"

#include "io/atomic_output.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "analysis/energy.hpp"
#include "run/resultants.hpp"
#include "run/output_regions.hpp"
#include "run/snapshot_fields.hpp"
#include "input/deck_error.hpp"
#include "io/vtu_writer.hpp"
#include "setup/build_model.hpp"
#include "solver/linear_static.hpp"

namespace periadapt {

namespace {

// The linear solve is a history law's elastic branch: valid while no breakable bond passes the
// law's onset stretch.
void refuse_beyond_elastic_branch(const Deck& dk, const Model& m) {
  const NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  double smax = -INFINITY;
  std::size_t at = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kNoFail)) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      if (!BondFamilies::intact(bf.beta[k]) || !bf.breakable(k)) continue;
      double xi[3], y[3];
      const double s = bond_vectors(ns, i, bf.neighbor[k], xi, y) / bf.length(k) - 1.0;
      if (s > smax) smax = s, at = i;
    }
  }
  if (smax > m.material.onset_stretch)
    throw DeckError(dk.file, 0, 0, "solver.type",
                    fmt::format("the linear static solve is the elastic branch of formulation {}, "
                                "but a bond of node {} at ({:.4g}, {:.4g}, {:.4g}) reaches stretch "
                                "{:.4g}, past the onset {:.4g}; use type: relaxation",
                                m.formulation.name(), at, ns.x[0][at], ns.x[1][at],
                                ns.x[2][at], smax, m.material.onset_stretch));
}

}  // namespace

void require_held_displacements(const Deck& dk) {
  for (const MotionSpec& ms : dk.motions)
    if (ms.kind == MotionSpec::Kind::Displacement &&
        std::any_of(ms.component.begin(), ms.component.end(), [](const auto& c) { return c.has_value(); }))
      return;
  throw DeckError(dk.file, dk.solver_type_at,
                  "a static solve needs boundary_conditions that prescribe displacements (the "
                  "body's rigid motions make the stiffness singular otherwise); for a free body "
                  "use type: explicit or relaxation");
}

RunResult run_static(const Deck& dk, const RunOptions& opt) {
  require_held_displacements(dk);
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  RunResult res;
  Model& m = res.model;
  m = build_model(dk);
  const NodeSet& ns = m.nodes;
  std::vector<DisplacementConstraint> cons;
  StaticResult sr;
  try {
    cons = model_constraints(m);
    StaticOptions so;
    so.pairing = dk.dual_horizon ? BondPairing::DualHorizon : BondPairing::SourceHorizon;
    sr = solve_linear_static(m, cons, so);
  } catch (const SingularSystem& e) {
    throw DeckError(dk.file, 0, 0, "boundary_conditions", e.what());
  } catch (const std::invalid_argument& e) {
    throw DeckError(dk.file, 0, 0, "boundary_conditions", e.what());
  }
  if (m.formulation.keeps_bond_history()) refuse_beyond_elastic_branch(dk, m);
  const double rel = sr.load_norm > 0 ? sr.residual_norm / sr.load_norm : sr.residual_norm;
  if (!opt.quiet)
    fmt::print("static solve: {} unknowns, {} nonzeros, {} ({} iterations), residual {:.3e} "
               "(relative {:.3e}), assembly {:.3f} s, solve {:.3f} s\n",
               sr.unknowns, sr.nonzeros, sr.iterative ? (sr.symmetric ? "CG (Jacobi)" : "BiCGSTAB") : sr.symmetric ? "sparse LDLT" : "sparse LU", sr.iterations,
               sr.residual_norm, rel, sr.assemble_seconds, sr.solve_seconds);

  std::vector<double> W;
  const double U = strain_energy(m, W);
  // Reactions from the linear operator that was solved (the nonlinear forces at this state
  // differ by the order of the strain), so that they balance the loads to the solver's residual.
  std::array<std::vector<double>, 3> f_int;
  {
    const auto K = assemble_bond_stiffness(
        ns, m.bonds, m.material.shape,
        dk.dual_horizon ? BondPairing::DualHorizon : BondPairing::SourceHorizon, &m.block_pairs);
    const int D = ns.dim;
    Eigen::VectorXd u(static_cast<Eigen::Index>(D * ns.size()));
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (int d = 0; d < D; ++d) u[static_cast<Eigen::Index>(D * i + d)] = ns.u[d][i];
    const Eigen::VectorXd f = K * u;
    for (int d = 0; d < 3; ++d) f_int[d].assign(ns.size(), 0.0);
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (int d = 0; d < D; ++d) f_int[d][i] = -f[static_cast<Eigen::Index>(D * i + d)];
  }
  nlohmann::json& j = res.summary;
  j["deck"] = dk.file;
  j["status"] = "completed";
  j["solver"] = {{"type", "static"},
                 {"bond_pairing", dk.dual_horizon ? "dual_horizon" : "source_horizon"},
                 {"method", sr.iterative ? (sr.symmetric ? "cg_jacobi" : "bicgstab") : sr.symmetric ? "sparse_ldlt" : "sparse_lu"},
                 {"iterations", sr.iterations},
                 {"unknowns", sr.unknowns},
                 {"nonzeros", sr.nonzeros},
                 {"constrained_components", cons.size()},
                 {"residual_norm", sr.residual_norm},
                 {"relative_residual", rel},
                 {"assemble_time_s", sr.assemble_seconds},
                 {"solve_time_s", sr.solve_seconds}};
  j["dimension"] = ns.dim;
  j["nodes"] = {{"initial", ns.size()}, {"final", ns.size()}};
  j["bonds"] = m.bonds.num_bonds();
  j["energy"] = {{"strain_J", U}};
  double umax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    for (int d = 0; d < ns.dim; ++d) umax = std::max(umax, std::abs(ns.u[d][i]));
  j["max_abs_displacement_m"] = umax;
  j["resultants"] = resultants_json(
      m, [&](const BodyLoad& l) { return load_force(ns, l, l.amplitude(1e300)); },
      [&](const PrescribedMotion& p) { return equilibrium_reaction(m, p, f_int, 1.0); });
  if (!dk.output.regions.empty()) j["regions"] = regions_json(dk.output.regions, ns, W, f_int);
  j["wall_time_s"] = std::chrono::duration<double>(clock::now() - t_start).count();
  if (opt.write_files) {
    const std::string dir = opt.out_dir ? *opt.out_dir : dk.output.directory;
    std::filesystem::create_directories(dir);
    VtuSeries vtu(dir, "snapshot", dk.output.vtu_zlib);
    vtu.write(0.0, ns, snapshot_fields(m, W, dk.output.stress));
    write_file_atomically(dir + "/displacement.csv", [&](std::ostream& csv) {
      csv << "node,x,y,z,ux,uy,uz\n";
      for (std::size_t i = 0; i < ns.size(); ++i)
        if (ns.flags[i] & kActive)
          csv << fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", i, ns.x[0][i],
                             ns.x[1][i], ns.x[2][i], ns.u[0][i], ns.u[1][i], ns.u[2][i]);
    });
    j["outputs"] = {{"pvd", vtu.pvd_path()}, {"displacement_csv", dir + "/displacement.csv"}};
    write_file_atomically(dir + "/summary.json", [&](std::ostream& o) { o << j.dump(2) << "\n"; });
  }
  return res;
}

}  // namespace periadapt
