#include "studies/pdro_sent.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "run/simulation.hpp"
#include "core/geometry.hpp"
#include "input/deck_error.hpp"
#include "studies/deck_variant.hpp"

namespace periadapt {

double sent_lefm_failure_stress(double E, double nu, double G0, double a, double W) {
  const double r = a / W, t = std::numbers::pi * r / 2.0;
  const double f = std::sqrt(2.0 * std::tan(t)) / std::cos(t) *
                   (0.752 + 2.02 * r + 0.37 * std::pow(1.0 - std::sin(t), 3));
  const double K_ic = std::sqrt(E * G0 / (1.0 - nu * nu));
  return K_ic / (std::sqrt(W) * f);
}

namespace {

struct SentRun {
  double dx = 0, n = 0;  // n = 0: no overlay
  std::size_t nodes = 0;
  double failure_stress = NAN, wall = 0, checks_per_eval = 0, angle = NAN;
};

SentRun run_variant(const PdroSentOptions& o, double dx, double n, const std::string& out_dir) {
  const std::string label = n > 0 ? fmt::format("dx {:.2f} mm, overlay n {:.3f}", 1e3 * dx, n)
                                  : fmt::format("dx {:.2f} mm", 1e3 * dx);
  const Deck dk = deck_variant(o.deck, label, [&](YAML::Node& d) {
    d["discretization"]["spacing"] = dx;
    if (n > 0) {
      d["damage"]["overlay"]["n"] = n;
      if (o.pim) d["damage"]["overlay"]["interpolation"] = "pim";
      if (o.gaussian) d["damage"]["overlay"]["weight"] = "gaussian";
      if (o.whole_bond) d["damage"]["overlay"]["sampling"] = "whole_bond";
    }
    d["output"]["history_every"] = 2;  // tip samples: failure time to 2 steps
    d["output"]["vtu_snapshots"] = 0;
  });
  if (dk.loads.empty()) throw DeckError(o.deck, 0, 0, "loads", "the SENT deck needs its traction");
  RunOptions ro;
  ro.quiet = true;
  ro.write_files = !out_dir.empty();
  if (!out_dir.empty())
    ro.out_dir = fmt::format("{}/sent_dx{:.2f}mm{}", out_dir, 1e3 * dx,
                             n > 0 ? fmt::format("_n{:.3f}", n) : std::string());
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult r = run_simulation(dk, ro);
  SentRun s;
  s.dx = dx;
  s.n = n;
  s.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.nodes = r.summary["nodes"]["final"].get<std::size_t>();
  const auto& c = r.summary["crack"];
  if (!c["initiation_time_s"].is_null()) {
    const LoadSpec& l = dk.loads[0];
    s.failure_stress = norm(l.value) * l.time(c["initiation_time_s"].get<double>());
  }
  if (c.contains("path_angle_deg")) s.angle = c["path_angle_deg"].get<double>();
  if (r.summary.contains("overlay"))
    s.checks_per_eval = r.summary["overlay"]["checks_per_bond_evaluation"].get<double>();
  return s;
}

}  // namespace

int run_pdro_sent_study(const std::string& out_dir, const PdroSentOptions& o) {
  const Deck base = deck_variant(o.deck, "base", [](YAML::Node&) {});
  if (base.cracks.empty() || !base.G0)
    throw DeckError(o.deck, 0, 0, "cracks", "the SENT deck needs an edge crack and fracture_energy");
  const double W = base.grid.body.hi[0] - base.grid.body.lo[0];
  const double a = norm(sub(base.cracks[0].points[1], base.cracks[0].points[0]));
  const double lefm = sent_lefm_failure_stress(base.E, 0.25, *base.G0, a, W);
  fmt::print("Stewart & Jeon 2019, 3.2: SENT, W = {:.0f} mm, a/W = {:.3f}; LEFM (Eqs. 11-12, plane "
             "strain, nu = 1/4): sigma_f = {:.4f} MPa. Failure: tip {:.1f} mm ahead of the notch.\n",
             1e3 * W, a / W, 1e-6 * lefm, 1e3 * base.output.tip_advance.value_or(base.grid.spacing));
  fmt::print("{:<28} {:>7} | {:>10} {:>8} | {:>9} | {:>7} {:>8}\n", "run", "nodes", "sigma_f MPa",
             "/LEFM", "/plain", "wall s", "checks");
  std::vector<SentRun> runs;
  for (double dx : o.native_spacings) runs.push_back(run_variant(o, dx, 0.0, out_dir));
  const double coarse = base.grid.spacing;
  const SentRun* plain = nullptr;
  for (const SentRun& r : runs)
    if (std::abs(r.dx - coarse) < 1e-12) plain = &r;
  std::vector<SentRun> ovl;
  for (double n : o.overlay_n) ovl.push_back(run_variant(o, coarse, n, out_dir));
  auto row = [&](const SentRun& r) {
    const std::string name = r.n > 0 ? fmt::format("{:.2f} mm + overlay n = {:.3f}", 1e3 * r.dx, r.n)
                                     : fmt::format("native {:.2f} mm", 1e3 * r.dx);
    fmt::print("{:<28} {:>7} | {:>10.4f} {:>8.3f} | {:>9} | {:>7.1f} {:>7.4f}%\n", name, r.nodes,
               1e-6 * r.failure_stress, r.failure_stress / lefm,
               plain ? fmt::format("{:.3f}", r.failure_stress / plain->failure_stress) : "-", r.wall,
               100 * r.checks_per_eval);
  };
  for (const SentRun& r : runs) row(r);
  for (const SentRun& r : ovl) row(r);
  if (!out_dir.empty()) {
    std::ofstream csv(out_dir + "/pdro_sent.csv");
    csv << "dx_m,overlay_n,nodes,failure_stress_Pa,lefm_Pa,wall_s,overlay_checks_per_bond_eval\n";
    for (const auto* set : {&runs, &ovl})
      for (const SentRun& r : *set)
        csv << fmt::format("{},{},{},{},{},{},{}\n", r.dx, r.n, r.nodes, r.failure_stress, lefm,
                           r.wall, r.checks_per_eval);
    fmt::print("wrote {}/pdro_sent.csv (and a directory per run)\n", out_dir);
  }
  return 0;
}

}  // namespace periadapt
