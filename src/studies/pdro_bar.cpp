#include "studies/pdro_bar.hpp"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "run/simulation.hpp"
#include "input/deck_builder.hpp"
#include "io/line_plot.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

namespace {

constexpr double kE = 72e9, kRho = 2400.0, kG0 = 6.0, kM = 4.0;

// Eq. 2 (plane strain): s0 = sqrt(5 pi G0 / (12 E delta)).
double s0_plane_strain(double delta) {
  return std::sqrt(5.0 * std::numbers::pi * kG0 / (12.0 * kE * delta));
}

struct BarResult {
  double strain_at_peak = 0, first_break_strain = 0, check_fraction = 0;
};

BarResult pull_bar(double dx, double n_overlay, const PdroBarOptions& o) {
  const double L = o.length, w = o.width, v = o.end_speed, delta = kM * dx;
  const double rate = 2.0 * v / L;
  const double target = n_overlay > 0 ? dx / n_overlay : dx;
  const double end_time = 1.6 * s0_plane_strain(kM * target) / rate;
  const std::string vx = fmt::format("{}*(2*x/{}-1)", v, L);
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("model.plane", "strain")
      .set("material.youngs_modulus", kE)
      .set("material.density", kRho)
      .set("material.fracture_energy", kG0)
      .set("discretization.spacing", dx)
      .set("discretization.horizon_factor", kM)
      .set("discretization.body.box.min", {0.0, -0.5 * w})
      .set("discretization.body.box.max", {L, 0.5 * w})
      .set("initial_conditions.velocity", std::vector<std::string>{vx, "0"})
      .set("solver.end_time", end_time);
  // The grips: a horizon at either end moves with the bar's initial velocity field.
  for (auto [lo, hi] : {std::pair{0.0, delta}, std::pair{L - delta, L}})
    d.append("boundary_conditions",
             DeckBuilder()
                 .set("region.box.min", {lo, -0.5 * w})
                 .set("region.box.max", {hi, 0.5 * w})
                 .set("velocity", std::vector<std::optional<std::string>>{vx, std::nullopt}));
  if (n_overlay > 0)
    d.set("damage.overlay.n", n_overlay)
        .set("damage.overlay.interpolation", o.pim ? "pim" : "pddo")
        .set("damage.overlay.weight", o.gaussian ? "gaussian" : "uniform")
        .set("damage.overlay.sampling", o.whole_bond ? "whole_bond" : "three_pairs");
  const Deck dk = d.build("pdro-bar (built-in)");
  Model m = build_model(dk);
  const TimeStepChoice ts = choose_time_step(dk, m);
  VelocityVerlet vv(m, ts.dt);
  vv.initialize();
  const NodeSet& ns = m.nodes;
  std::vector<std::size_t> right;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > L - delta) right.push_back(i);
  BarResult r;
  double pmax = 0;
  for (long s = 1; s <= ts.steps; ++s) {
    if (!vv.step()) break;
    const double strain = rate * vv.time();
    double p = 0;  // end load: the bar's pull on the right grip
    for (std::size_t i : right) p -= ns.f[0][i] * ns.volume[i];
    if (p > pmax) pmax = p, r.strain_at_peak = strain;
    if (vv.broken_bonds() > 0 && r.first_break_strain == 0) r.first_break_strain = strain;
    if (vv.broken_bonds() > 0 && p < 0.5 * pmax) break;  // separated
  }
  if (n_overlay > 0 && vv.bond_evaluations() > 0)
    r.check_fraction = static_cast<double>(m.pdro.counters->checks.load()) / vv.bond_evaluations();
  return r;
}

}  // namespace

std::vector<PdroBarRow> pdro_bar_rows(const PdroBarOptions& o) {
  std::vector<PdroBarRow> rows;
  for (double t : o.targets) {
    PdroBarRow row;
    row.target = t;
    row.n = o.coarse / t;
    row.s0_eq2 = s0_plane_strain(kM * t);
    row.native_strain = pull_bar(t, 0.0, o).strain_at_peak;
    const BarResult ov = pull_bar(o.coarse, row.n, o);
    row.overlay_strain = ov.strain_at_peak;
    row.overlay_check_fraction = ov.check_fraction;
    rows.push_back(row);
  }
  return rows;
}

int run_pdro_bar_study(const std::string& out_dir, const PdroBarOptions& o) {
  fmt::print(
      "Stewart & Jeon 2019, 3.1: plane-strain bar {:.0f} x {:.0f} mm pulled at {} m/s per end "
      "(homogeneous start), m = 4, G0 = 6 J/m^2; native grids vs a {:.1f} mm grid with the "
      "overlay ({})\n",
      1e3 * o.length, 1e3 * o.width, o.end_speed, 1e3 * o.coarse,
      o.pim ? "PIM" : o.gaussian ? "PDDO, Gaussian weight" : "PDDO, uniform weight");
  const double s0_coarse = s0_plane_strain(kM * o.coarse);
  const double plain = pull_bar(o.coarse, 0.0, o).strain_at_peak;
  fmt::print("coarse grid without overlay: failure strain {:.4e} (Eq. 2: {:.4e})\n", plain,
             s0_coarse);
  fmt::print("{:>8} {:>6} | {:>10} | {:>10} {:>7} | {:>10} {:>7} | {:>8} | {:>8}\n", "dx' mm",
             "n", "Eq. 2 s0", "native", "/Eq.2", "overlay", "/Eq.2", "ovl/nat", "checks");
  const std::vector<PdroBarRow> rows = pdro_bar_rows(o);
  PlotSeries eq{"Eq. 2", {}, {}}, nat{"native grid", {}, {}}, ovl{"1 mm grid + overlay", {}, {}};
  for (const PdroBarRow& r : rows) {
    fmt::print("{:>8.2f} {:>6.3f} | {:>10.4e} | {:>10.4e} {:>7.4f} | {:>10.4e} {:>7.4f} | {:>8.4f} "
               "| {:>7.2f}%\n",
               1e3 * r.target, r.n, r.s0_eq2, r.native_strain, r.native_strain / r.s0_eq2,
               r.overlay_strain, r.overlay_strain / r.s0_eq2, r.overlay_strain / r.native_strain,
               100 * r.overlay_check_fraction);
    for (PlotSeries* p : {&eq, &nat, &ovl}) p->x.push_back(1e3 * r.target);
    eq.y.push_back(r.s0_eq2);
    nat.y.push_back(r.native_strain);
    ovl.y.push_back(r.overlay_strain);
  }
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
    std::ofstream csv(out_dir + "/pdro_bar.csv");
    csv << "target_dx_m,n,s0_eq2,native_failure_strain,overlay_failure_strain,overlay_check_fraction\n";
    for (const PdroBarRow& r : rows)
      csv << fmt::format("{},{},{},{},{},{}\n", r.target, r.n, r.s0_eq2, r.native_strain,
                         r.overlay_strain, r.overlay_check_fraction);
    PlotOptions po;
    po.title = "Bar failure strain vs target grid spacing (Stewart & Jeon Fig. 6)";
    po.x_label = "dx' (mm)";
    po.y_label = "remote strain at failure";
    write_line_plot(out_dir + "/pdro_bar.png", {eq, nat, ovl}, po);
    fmt::print("wrote {0}/pdro_bar.csv and {0}/pdro_bar.png\n", out_dir);
  }
  return 0;
}

}  // namespace periadapt
