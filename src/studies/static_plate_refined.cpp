#include "studies/static_plate_refined.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <cmath>

#include "run/static_run.hpp"
#include "input/deck.hpp"
#include "io/line_plot.hpp"
#include "studies/plate_error_profiles.hpp"
#include "studies/study_csv.hpp"

namespace periadapt {

namespace {


struct Variant {
  const char* name;
  const char* pairing;
  const char* correction;  // deck value of discretization.surface_correction
  bool interface_fit = false;  // adapt.interface_fit
};

const Variant kVariants[7] = {{"scaling", "source_horizon", "false"},
                              {"scaling + interface fit", "source_horizon", "false", true},
                              {"scaling + moment correction", "source_horizon", "moments"},
                              {"scaling + moments + interface fit", "source_horizon", "moments", true},
                              {"scaling + DH", "dual_horizon", "false"},
                              {"scaling + DH + surface correction", "dual_horizon", "energy"},
                              {"scaling + DH + moment correction", "dual_horizon", "moments"}};

// The plate with one half at `level`; nullopt (and a line saying why) where there is no solution.
std::optional<RunResult> solve_half_refined(const Variant& v, int level, bool upper, char model) {
  if (level == 3 && std::string(v.pairing) == "source_horizon") {
    // Plain scaling at level 3 (440,000 unknowns, non-symmetric, ghost forces at a 8:1
    // horizon jump) defeats Jacobi-BiCGSTAB and the sparse LU here; skipped.
    fmt::print("{:<6} {:<34} skipped (non-symmetric system beyond our solvers' reach)\n", model, v.name);
    return std::nullopt;
  }
  Deck dk = tension_plate_deck(v.correction, v.pairing, level, upper,
                               "static-plate-refined (built-in)");
  dk.adapt.interface_fit = v.interface_fit;
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  try {
    return run_static(dk, ro);
  } catch (const std::exception& ex) {
    fmt::print("{:<6} {:<34} no solution: {}\n", model, v.name, ex.what());
    return std::nullopt;
  }
}

// Mean u_x (relative to the exact p x / E) of the nodes on the vertical line x = `at`, over y in
// [lo, hi]: the in-plane bending the thesis sees in Fig. 4.21.
double mean_ux_ratio(const NodeSet& ns, double at, double lo, double hi, double p, double E) {
  double s = 0;
  int n = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double X = ns.x[0][i], Y = ns.x[1][i];
    if (std::abs(X - at) <= 0.5 * ns.spacing[i] * (1 + 1e-9) && Y >= lo && Y <= hi)
      s += ns.u[0][i] / (p * X / E), ++n;
  }
  return n ? s / n : 0.0;
}

// One model's error profiles: CSV rows (model, level, variant, coordinate, error) and a PNG.
void append_profile(std::ofstream& csv, char model, int level, const Variant& v,
                    const std::vector<double>& at, const std::vector<double>& err,
                    std::vector<PlotSeries>& series) {
  if (csv)
    for (std::size_t k = 0; k < at.size(); ++k)
      csv << fmt::format("{},{},{},{:.6g},{:.6g}\n", model, level, v.name, at[k], err[k]);
  series.push_back({v.name, at, err});
}

void plot_profiles(const std::string& out_dir, const std::string& file, const std::string& title,
                   const char* axis, const std::vector<PlotSeries>& series) {
  if (out_dir.empty()) return;
  PlotOptions po;
  po.title = title;
  po.x_label = axis;
  po.y_label = "error (%)";
  write_line_plot(out_dir + "/" + file, series, po);
}

}  // namespace

int run_static_plate_refined_study(const std::string& out_dir) {
  std::ofstream csv = open_study_csv(out_dir, "static_plate_refined_errors.csv",
                                     "model,level,variant,x_m,error_ux_pct");
  fmt::print("Thesis 4.1, left half refined (models A-C): |e(u_x)| on the horizontal centre line (%);\n"
             "peak over the coarse side 0.01 <= x <= 0.45 m, plateaus: mean over x in [-0.4, -0.1] (refined) and "
             "[0.1, 0.4] (coarse)\n");
  fmt::print("{:<6} {:<34} {:>8} {:>9} {:>9} {:>9} {:>8}\n", "model", "variant", "nodes",
             "peak", "refined", "coarse", "L2");
  for (int level = 1; level <= 3; ++level) {
    std::vector<PlotSeries> series;
    for (const Variant& v : kVariants) {
      const char model = static_cast<char>('A' + level - 1);
      const std::optional<RunResult> solved = solve_half_refined(v, level, false, model);
      if (!solved) continue;
      const RunResult& r = *solved;
      const PlateErrors e = plate_errors(r.model.nodes, 200e6, 200e9, 1.0 / 3.0);
      // Plateaus away from the loaded edges and from the interface at x = 0.
      // Peak on the coarse side, as the thesis reports it (x >= 0.01 m: at x -> 0 the exact u_x
      // vanishes and relative errors lose meaning; the refined side carries a small interface
      // offset, visible in the CSV).
      const double peak = e.max_ex(0.01, 0.45);
      fmt::print("{:<6} {:<34} {:>8} {:>9.2f} {:>9.2f} {:>9.2f} {:>8.2f}\n", model, v.name,
                 r.summary["nodes"]["final"].get<std::size_t>(), peak,
                 e.mean_ex(-0.4, -0.1), e.mean_ex(0.1, 0.4), e.l2);
      append_profile(csv, model, level, v, e.x, e.ex, series);
    }
    const char model = static_cast<char>('A' + level - 1);
    plot_profiles(out_dir, fmt::format("static_plate_refined_model_{}.png", model),
                  fmt::format("Model {} (left half at level {}): error of u_x, horizontal centre line",
                              model, level),
                  "x (m)", series);
  }
  fmt::print("thesis (scaling & DH): peak about 31.5% in the coarse interface zone at every level; "
             "plateaus about 7% (refined) and 5% (coarse); with surface correction 1.5% and 2%\n");
  return 0;
}

int run_static_plate_upper_study(const std::string& out_dir) {
  std::ofstream csv = open_study_csv(out_dir, "static_plate_upper_errors.csv",
                                     "model,level,variant,y_m,error_uy_pct");
  fmt::print("Thesis 4.1, upper half refined (models D-F): |e(u_y)| on the vertical centre line (%);\n"
             "peaks over the refined side 0.01 <= y <= 0.24 m and the coarse side, plateaus: mean over |y| in "
             "[0.05, 0.2]; u_x / (p x / E) on the line x = 0.2 m, refined and coarse side (bending)\n");
  fmt::print("{:<6} {:<34} {:>8} {:>9} {:>9} {:>9} {:>9} {:>8} {:>9} {:>9}\n", "model", "variant",
             "nodes", "peak ref", "peak crs", "plat ref", "plat crs", "L2", "ux/ex ref", "ux/ex crs");
  for (int level = 1; level <= 3; ++level) {
    std::vector<PlotSeries> series;
    const char model = static_cast<char>('D' + level - 1);
    for (const Variant& v : kVariants) {
      const std::optional<RunResult> solved = solve_half_refined(v, level, true, model);
      if (!solved) continue;
      const NodeSet& ns = solved->model.nodes;
      const PlateErrors e = plate_errors(ns, 200e6, 200e9, 1.0 / 3.0);
      fmt::print("{:<6} {:<34} {:>8} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>8.2f} {:>9.4f} {:>9.4f}\n",
                 model, v.name, solved->summary["nodes"]["final"].get<std::size_t>(),
                 e.max_ey(0.01, 0.24), e.max_ey(-0.24, -0.01), e.mean_ey(0.05, 0.2),
                 e.mean_ey(-0.2, -0.05), e.l2, mean_ux_ratio(ns, 0.2, 0.01, 0.24, 200e6, 200e9),
                 mean_ux_ratio(ns, 0.2, -0.24, -0.01, 200e6, 200e9));
      append_profile(csv, model, level, v, e.y, e.ey, series);
    }
    plot_profiles(out_dir, fmt::format("static_plate_upper_model_{}.png", model),
                  fmt::format("Model {} (upper half at level {}): error of u_y, vertical centre line",
                              model, level),
                  "y (m)", series);
  }
  fmt::print("thesis (scaling & DH, Figs. 4.12-4.21): largest u_y error about 15% on the refined side; "
             "u_x on x = 0.2 m larger on the coarse side than on the refined one (in-plane bending)\n");
  return 0;
}

}  // namespace periadapt
