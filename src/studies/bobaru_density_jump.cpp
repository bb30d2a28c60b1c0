#include "studies/bobaru_density_jump.hpp"

#include <fmt/core.h>

#include <cmath>
#include <fstream>

#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"
#include "studies/bobaru_1d_wave.hpp"
#include "studies/study_csv.hpp"

namespace periadapt {

DensityJumpReflection bobaru_density_jump(int density_factor, const std::string& shape,
                                          double coarse_spacing, double time_step,
                                          bool dual_horizon, bool lattice) {
  // The middle third refined by m-scaling, which keeps the horizon and divides the spacing by 2
  // per level, without widening the zone (visibility off). The zone's box takes the whole cells
  // of the nodes at 100 and 200, so that the density jumps at once (no level-1 fringe).
  DeckBuilder b;
  b.set("model.dimension", 1)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("material.micromodulus", shape)
      .set("discretization.spacing", coarse_spacing)
      .set("discretization.horizon", 0.5)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", "subcell")
      .set("discretization.micromodulus_calibration", lattice ? "lattice" : "analytic")
      .set("discretization.body.box.min", {0.0})
      .set("discretization.body.box.max", {300.0})
      .set("initial_conditions.displacement", std::vector<std::string>{"0.02*exp(-0.01*x^2)"})
      .set("damage.enabled", false)
      .set("solver.end_time", 300.0)
      .set("solver.time_step", time_step)
      .set("solver.bond_pairing", dual_horizon ? "dual_horizon" : "source_horizon");
  if (density_factor > 1) {
    const int level = density_factor == 2 ? 1 : 2;
    b.set("adapt.scaling", "m").set("adapt.visibility", false);
    b.append("adapt.initial_refinement",
             DeckBuilder()
                 .set("region.box.min", {100.0 - 0.5 * coarse_spacing})
                 .set("region.box.max", {200.0 + 0.5 * coarse_spacing})
                 .set("level", level));
  }
  const Deck dk = b.build("bobaru-1d-density-jump (built-in)");
  Model m = build_model(dk);
  VelocityVerlet vv(m, time_step);
  vv.initialize();
  // The main pulse has passed x = 150 long before t = 200 (width ~10); the reflection from
  // x = 100 runs left and returns only after t = 350.
  PeakTracker peak;
  peak.magnitude = true;
  const long steps = std::lround(dk.end_time / time_step);
  for (long s = 1; s <= steps; ++s) {
    vv.step();
    peak.sample(vv.time(), bar_displacement_at(m.nodes, 150.0), time_step, vv.time() >= 200.0);
  }
  DensityJumpReflection r;
  r.time = peak.time;
  r.amplitude = peak.value;
  // The long pulse sees each grid as a bar of modulus E_eff = 1/2 sum_j c(xi) |xi| V_j beta_j
  // (the quadrature of the calibration integral): nodes in the middle of each region.
  auto e_eff = [&](double x) {
    const NodeSet& ns = m.nodes;
    std::size_t i = 0;
    for (std::size_t k = 0; k < ns.size(); ++k)
      if ((ns.flags[k] & kActive) && std::abs(ns.x[0][k] - x) < std::abs(ns.x[0][i] - x)) i = k;
    double e = 0;
    for (std::size_t b = m.bonds.begin(i); b < m.bonds.end(i); ++b) {
      const double xi = 1.0 / std::abs(m.bonds.inv_length[b]);
      e += 0.5 * ns.micromodulus[i] * influence(dk.shape, xi / ns.horizon[i]) * xi *
           ns.volume[m.bonds.neighbor[b]] * m.bonds.beta[b];
    }
    return e;
  };
  r.modulus_coarse = e_eff(50.0);
  r.modulus_dense = e_eff(150.0);
  return r;
}

int run_bobaru_density_jump_study(const std::string& out_dir, bool quick) {
  struct Row {
    int factor;
    const char* shape;
    double arrival, amplitude_e4;
  };
  const Row rows[4] = {{2, "constant", 252.15, 1.169},
                       {2, "triangular", 249.15, 0.0844},
                       {4, "constant", 252.30, 3.3557},
                       {4, "triangular", 252.30, 1.4945}};
  std::ofstream csv = open_study_csv(
      out_dir, "bobaru_density_jump.csv",
      "density_factor,micromodulus,coarse_spacing,arrival,amplitude,reflected_pct,pub_arrival,pub_reflected_pct");
  fmt::print("Bobaru et al. 2009, Table III (node density x2 / x4 on [100, 200], horizon 0.5 "
             "everywhere; reflected peak at x = 150, exact arrival 250, main amplitude 0.01)\n");
  fmt::print("{:>4} {:>11} | {:>9} {:>9} | {:>12} {:>10} {:>10} | {:>9} {:>9} | {:>10}\n", "case",
             "shape", "T ours", "T pub.", "A ours e-4", "refl. %", "pub. %", "E coarse", "E dense",
             "no jump %");
  for (const Row& r : rows) {
    const DensityJumpReflection a = bobaru_density_jump(r.factor, r.shape);
    const DensityJumpReflection floor = bobaru_density_jump(1, r.shape);
    const double pct = 100 * std::abs(a.amplitude) / 0.01;
    fmt::print("{:>4} {:>11} | {:>9.2f} {:>9.2f} | {:>+12.4f} {:>10.4f} {:>10.4f} | {:>9.5f} {:>9.5f} | {:>10.4f}\n",
               r.factor == 2 ? "(a)" : "(b)", r.shape, a.time, r.arrival, 1e4 * a.amplitude, pct,
               r.amplitude_e4, a.modulus_coarse, a.modulus_dense, 100 * std::abs(floor.amplitude) / 0.01);
    if (csv)
      csv << fmt::format("{},{},0.2,{:.6g},{:.6g},{:.6g},{},{}\n", r.factor, r.shape, a.time,
                         a.amplitude, pct, r.arrival, r.amplitude_e4);
  }
  // The reflection is the quadrature's: with every spacing divided by 4 (m = 10 outside, 20 and 40
  // inside) both grids integrate the bond stiffness closely and it falls by 4-250x.
  if (quick) return 0;
  // What the reflection is made of. With the source-horizon pairing a bond across the jump pulls
  // its two ends with different partial volumes (beta_ij V_j against beta_ji V_i): the interface
  // does not pass the traction it receives. The dual-horizon pairing makes every bond reciprocal;
  // what remains is the impedance jump of the two grids' bond stiffness, whose long-wave
  // reflection is (sqrt(E_dense) - sqrt(E_coarse)) / (sqrt(E_dense) + sqrt(E_coarse)) for a
  // pulse leaving the dense grid. Lattice calibration gives both grids the continuum's stiffness.
  fmt::print("Where it comes from (reflected %, signed): source-horizon pairing | dual horizon, "
             "impedance prediction | dual horizon + lattice calibration\n");
  for (const Row& r : rows) {
    const DensityJumpReflection sh = bobaru_density_jump(r.factor, r.shape);
    const DensityJumpReflection dh = bobaru_density_jump(r.factor, r.shape, 0.2, 0.02, true);
    const DensityJumpReflection dl = bobaru_density_jump(r.factor, r.shape, 0.2, 0.02, true, true);
    const double ed = std::sqrt(dh.modulus_dense), ec = std::sqrt(dh.modulus_coarse);
    const double pred = 100 * (ed - ec) / (ed + ec);
    fmt::print("{:>4} {:>11} | {:>+9.4f} | {:>+9.4f} {:>+9.4f} | {:>+9.4f}\n", r.factor == 2 ? "(a)" : "(b)",
               r.shape, 100 * sh.amplitude / 0.01, 100 * dh.amplitude / 0.01, pred,
               100 * dl.amplitude / 0.01);
    if (csv) {
      csv << fmt::format("{},{},0.2-dual,{:.6g},{:.6g},{:.6g},,\n", r.factor, r.shape, dh.time,
                         dh.amplitude, 100 * std::abs(dh.amplitude) / 0.01);
      csv << fmt::format("{},{},0.2-dual-lattice,{:.6g},{:.6g},{:.6g},,\n", r.factor, r.shape,
                         dl.time, dl.amplitude, 100 * std::abs(dl.amplitude) / 0.01);
    }
  }
  fmt::print("The same with every spacing / 4 (coarse 0.05)\n");
  for (const Row& r : rows) {
    const DensityJumpReflection a = bobaru_density_jump(r.factor, r.shape, 0.05);
    const double pct = 100 * std::abs(a.amplitude) / 0.01;
    fmt::print("{:>4} {:>11} | {:>9.2f} {:>9} | {:>+12.4f} {:>10.4f} {:>10} | {:>9.5f} {:>9.5f} |\n",
               r.factor == 2 ? "(a)" : "(b)", r.shape, a.time, "", 1e4 * a.amplitude, pct, "",
               a.modulus_coarse, a.modulus_dense);
    if (csv)
      csv << fmt::format("{},{},0.05,{:.6g},{:.6g},{:.6g},,\n", r.factor, r.shape, a.time, a.amplitude, pct);
  }
  return 0;
}

}  // namespace periadapt
