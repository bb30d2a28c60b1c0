#include "studies/bobaru_1d_wave.hpp"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <fstream>

#include "adapt/adaptor.hpp"
#include "discretize/lattice_moment.hpp"
#include "run/simulation.hpp"
#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"
#include "studies/convergence_rate.hpp"
#include "studies/study_csv.hpp"

namespace periadapt {

double bar_displacement_at(const NodeSet& ns, double x) {
  // Linear interpolation between the active nodes around x (refinement moves them).
  std::size_t lo = ns.size(), hi = ns.size();
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double xi = ns.x[0][i];
    if (xi <= x && (lo == ns.size() || xi > ns.x[0][lo])) lo = i;
    if (xi >= x && (hi == ns.size() || xi < ns.x[0][hi])) hi = i;
  }
  if (lo == hi) return ns.u[0][lo];
  const double w = (x - ns.x[0][lo]) / (ns.x[0][hi] - ns.x[0][lo]);
  return (1 - w) * ns.u[0][lo] + w * ns.u[0][hi];
}

// Peak of u(400, t): the largest sample refined by a parabola through its neighbours.
WaveArrival bobaru_wave_arrival(int nodes, double delta, bool adaptive, const std::string& scaling,
                                bool lattice) {
  const double dx = 450.0 / (nodes - 1);
  DeckBuilder d;
  d.set("model.dimension", 1)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("material.micromodulus", "triangular")
      .set("discretization.spacing", dx)
      .set("discretization.horizon", delta)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", "subcell")
      .set("discretization.body.box.min", {0.0})
      .set("discretization.body.box.max", {450.0})
      .set("discretization.micromodulus_calibration", lattice ? "lattice" : "analytic")
      .set("initial_conditions.displacement", std::vector<std::string>{"0.02*exp(-0.01*x^2)"})
      .set("damage.enabled", false)
      .set("solver.end_time", 460.0)
      .set("solver.time_step", 0.25 * dx)
      .set("solver.bond_pairing", "dual_horizon");
  if (adaptive) {
    d.set("adapt.max_level", 1)
        .set("adapt.energy_trigger", 0.75)
        .set("adapt.energy", "total")
        .set("adapt.coarsen", true)
        .set("adapt.visibility_factor", 6)
        .set("adapt.scaling", scaling);
    // delta-m: m grows by one per level (thesis Table 4.5: 3, 4, 5, 6).
    if (scaling == "delta_m") d.set("adapt.m_per_level", {delta / dx, delta / dx + 1});
    // Zones whose horizon differs from the coarse grid's differ in dispersion and pump energy as
    // they move (+103% by t = 400 on 2,701 nodes with delta-scaling; delta-m: amplitude at
    // x = 400 +9.9%); m-scaling ones do not (+1.3%) and are left alone.
    if (scaling != "m") d.set("adapt.conserve_energy", true);
  }
  const Deck dk = d.build("bobaru-1d-wave (built-in)");
  Model m = build_model(dk);
  const TimeStepChoice ts = choose_time_step(dk, m);
  VelocityVerlet vv(m, ts.dt);
  vv.initialize();
  std::unique_ptr<Adaptor> ad;
  if (adaptive) ad = std::make_unique<Adaptor>(m, vv, dk.adapt);
  double node_sum = 0;
  PeakTracker peak;
  WaveArrival a;
  a.min_nodes = m.nodes.size();
  for (long s = 1; s <= ts.steps; ++s) {
    if (ad) ad->step();
    else vv.step();
    std::size_t active = 0;
    for (auto f : m.nodes.flags) active += (f & kActive) != 0;
    node_sum += static_cast<double>(active);
    a.min_nodes = std::min(a.min_nodes, active);
    a.max_nodes = std::max(a.max_nodes, active);
    peak.sample(vv.time(), bar_displacement_at(m.nodes, 400.0), ts.dt);
  }
  a.time = peak.time;
  a.amplitude = peak.value;
  a.mean_nodes = node_sum / static_cast<double>(ts.steps);
  return a;
}

int run_bobaru_1d_wave_study(const std::string& out_dir) {
  struct Row {
    int nodes;
    double delta, arrival, amplitude;
  };
  const Row rows[5] = {{451, 3.0, 426.60, 0.00970},
                       {901, 2.5, 409.95, 0.00982},
                       {1351, 2.0, 406.80, 0.00991},
                       {2701, 1.5, 403.20, 0.00997},
                       {3001, 1.4, 402.15, 0.00998}};
  std::ofstream csv = open_study_csv(out_dir, "bobaru_1d_wave.csv",
                                     "nodes,delta,arrival,amplitude,err_arrival_pct,err_amplitude_pct,pub_arrival,pub_amplitude");
  fmt::print("Bobaru et al. 2009, Table IV (uniform grids, triangular micromodulus, peak at x = 400;"
             " exact T = 400, A = 0.01)\n");
  fmt::print("{:>6} {:>6} | {:>9} {:>9} {:>8} | {:>9} {:>9} {:>8} | {:>10} {:>10}\n", "nodes",
             "delta", "T ours", "T pub.", "err %", "A ours", "A pub.", "err %", "pub err T",
             "pub err A");
  std::vector<double> n, et, ea;
  for (const Row& r : rows) {
    const WaveArrival a = bobaru_wave_arrival(r.nodes, r.delta);
    const double eT = 100 * std::abs(a.time - 400) / 400, eA = 100 * std::abs(a.amplitude - 0.01) / 0.01;
    const double pT = 100 * std::abs(r.arrival - 400) / 400, pA = 100 * std::abs(r.amplitude - 0.01) / 0.01;
    fmt::print("{:>6} {:>6.2f} | {:>9.2f} {:>9.2f} {:>8.2f} | {:>9.5f} {:>9.5f} {:>8.2f} | {:>10.2f} {:>10.2f}\n",
               r.nodes, r.delta, a.time, r.arrival, eT, a.amplitude, r.amplitude, eA, pT, pA);
    if (csv)
      csv << fmt::format("{},{},{:.6g},{:.6g},{:.4g},{:.4g},{},{}\n", r.nodes, r.delta, a.time,
                         a.amplitude, eT, eA, r.arrival, r.amplitude);
    n.push_back(r.nodes), et.push_back(eT), ea.push_back(eA);
  }
  fmt::print("rates (vs nodes): arrival {:.3f} (published 1.245), amplitude {:.3f} (published 1.371)\n",
             fitted_rate(n, et), fitted_rate(n, ea));
  // Most of these arrival errors are the quadrature's: the triangular kernel's midpoint sum gives
  // the bar a modulus k E (k = 1 - 1/m^2 at integer m), so the pulse travels at sqrt(k) and
  // arrives at 400/sqrt(k); calibrating the micromodulus to the lattice leaves the dispersion.
  fmt::print("The same grids with micromodulus_calibration: lattice, beside the arrival that the "
             "quadrature's bond stiffness k alone gives\n");
  fmt::print("{:>6} {:>6} {:>6} | {:>9} {:>8} | {:>9} {:>8} | {:>8} {:>11}\n", "nodes", "delta", "m",
             "T", "err %", "A", "err %", "k", "400/sqrt(k)");
  for (const Row& r : rows) {
    const WaveArrival a = bobaru_wave_arrival(r.nodes, r.delta, false, "delta", true);
    const double m = r.delta / (450.0 / (r.nodes - 1));
    const double k = lattice_bond_moment(Quadrature::Subcell, 1, InfluenceShape::Triangular, m);
    fmt::print("{:>6} {:>6.2f} {:>6.3f} | {:>9.2f} {:>8.2f} | {:>9.5f} {:>8.2f} | {:>8.5f} {:>11.2f}\n",
               r.nodes, r.delta, m, a.time, 100 * std::abs(a.time - 400) / 400, a.amplitude,
               100 * std::abs(a.amplitude - 0.01) / 0.01, k, 400 / std::sqrt(k));
    if (csv)
      csv << fmt::format("{}-lattice,{},{:.6g},{:.6g},{:.4g},{:.4g},,\n", r.nodes, r.delta, a.time,
                         a.amplitude, 100 * std::abs(a.time - 400) / 400,
                         100 * std::abs(a.amplitude - 0.01) / 0.01);
  }
  fmt::print("\n");

  // Table V: the same grids with level-1 AGRS following the pulse (total-energy trigger at 75%,
  // 6 horizons around, coarsening behind, dual-horizon bonds; delta-scaling with energy-conserving
  // events). Published
  // values as reconstructed in the spec (Table V is garbled). The arrival error of these grids is
  // set by m = delta/dx (uniform dx = 0.5 with delta = 1.5 arrives like dx = 1 with delta = 3):
  // delta-scaling keeps m = 3 in the refined zone and cannot gain much; m-scaling (delta kept, m
  // doubled) and delta-m scaling (m + 1, delta * (m + 1) / 2m) are shown beside it. "uniform
  // same N": the Table IV error at the adaptive run's mean node count (log-log interpolation
  // between our uniform rows).
  auto uniform_at = [&](double N, const std::vector<double>& err) {
    std::size_t k = 1;
    while (k + 1 < n.size() && n[k] < N) ++k;
    const double t = std::log(N / n[k - 1]) / std::log(n[k] / n[k - 1]);
    return std::exp(std::log(err[k - 1]) + t * (std::log(err[k]) - std::log(err[k - 1])));
  };
  const Row adaptive[5] = {{451, 3.0, 415.35, 0.00987},
                           {901, 2.5, 405.90, 0.00991},
                           {1351, 2.0, 403.95, 0.00996},
                           {2701, 1.5, 401.85, 0.00999},
                           {3001, 1.4, 401.40, 0.01000}};
  for (const char* scaling : {"delta", "m", "delta_m"}) {
    fmt::print("Table V (adaptive refinement and coarsening, {}-scaling)\n", scaling);
    fmt::print("{:>6} {:>16} | {:>9} {:>9} {:>8} {:>11} | {:>9} {:>9} {:>8} {:>11}\n", "nodes",
               "active (mean)", "T ours", "T pub.", "err %", "unif same N", "A ours", "A pub.",
               "err %", "unif same N");
    std::vector<double> na, eta, eaa;
    for (const Row& r : adaptive) {
      const WaveArrival a = bobaru_wave_arrival(r.nodes, r.delta, true, scaling);
      const double eT = 100 * std::abs(a.time - 400) / 400;
      const double eA = 100 * std::abs(a.amplitude - 0.01) / 0.01;
      fmt::print("{:>6} {:>5}-{:<5}({:>4.0f}) | {:>9.2f} {:>9.2f} {:>8.2f} {:>11.2f} | {:>9.5f} {:>9.5f} "
                 "{:>8.2f} {:>11.2f}\n",
                 r.nodes, a.min_nodes, a.max_nodes, a.mean_nodes, a.time, r.arrival, eT,
                 uniform_at(a.mean_nodes, et), a.amplitude, r.amplitude, eA,
                 uniform_at(a.mean_nodes, ea));
      if (csv)
        csv << fmt::format("{}-adaptive-{},{},{:.6g},{:.6g},{:.4g},{:.4g},{},{}\n", r.nodes, scaling,
                           r.delta, a.time, a.amplitude, eT, eA, r.arrival, r.amplitude);
      na.push_back(a.mean_nodes), eta.push_back(eT), eaa.push_back(std::max(eA, 1e-6));
    }
    fmt::print("rates (vs mean nodes): arrival {:.3f} (published 1.234), amplitude {:.3f} "
               "(published 1.492)\n\n",
               fitted_rate(na, eta), fitted_rate(na, eaa));
  }
  return 0;
}

}  // namespace periadapt
