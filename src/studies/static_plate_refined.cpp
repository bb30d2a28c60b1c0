#include "studies/static_plate_refined.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

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
};

}  // namespace

int run_static_plate_refined_study(const std::string& out_dir) {
  const Variant variants[4] = {{"scaling", "source_horizon", "false"},
                               {"scaling + DH", "dual_horizon", "false"},
                               {"scaling + DH + surface correction", "dual_horizon", "energy"},
                               {"scaling + DH + moment correction", "dual_horizon", "moments"}};
  std::ofstream csv = open_study_csv(out_dir, "static_plate_refined_errors.csv",
                                     "model,level,variant,x_m,error_ux_pct");
  fmt::print("Thesis 4.1, left half refined (models A-C): |e(u_x)| on the horizontal centre line (%);\n"
             "peak over the coarse side 0.01 <= x <= 0.45 m, plateaus: mean over x in [-0.4, -0.1] (refined) and "
             "[0.1, 0.4] (coarse)\n");
  fmt::print("{:<6} {:<34} {:>8} {:>9} {:>9} {:>9} {:>8}\n", "model", "variant", "nodes",
             "peak", "refined", "coarse", "L2");
  for (int level = 1; level <= 3; ++level) {
    std::vector<PlotSeries> series;
    for (const Variant& v : variants) {
      if (level == 3 && std::string(v.pairing) == "source_horizon") {
        // Plain scaling at level 3 (440,000 unknowns, non-symmetric, ghost forces at a 8:1
        // horizon jump) defeats Jacobi-BiCGSTAB and the sparse LU here; skipped.
        fmt::print("{:<6} {:<34} skipped (non-symmetric system beyond our solvers' reach)\n", "C",
                   v.name);
        continue;
      }
      const Deck dk = parse_deck(tension_plate_deck(v.correction, v.pairing, level),
                                 "static-plate-refined (built-in)");
      RunOptions ro;
      ro.write_files = false;
      ro.quiet = true;
      const char model = static_cast<char>('A' + level - 1);
      RunResult r;
      try {
        r = run_static(dk, ro);
      } catch (const std::exception& ex) {
        // Plain scaling at level 3 leaves a system our solvers cannot resolve: report it.
        fmt::print("{:<6} {:<34} no solution: {}\n", model, v.name, ex.what());
        continue;
      }
      const PlateErrors e = plate_errors(r.model.nodes, 200e6, 200e9, 1.0 / 3.0);
      // Plateaus away from the loaded edges and from the interface at x = 0.
      // Peak on the coarse side, as the thesis reports it (x >= 0.01 m: at x -> 0 the exact u_x
      // vanishes and relative errors lose meaning; the refined side carries a small interface
      // offset, visible in the CSV).
      const double peak = e.max_ex(0.01, 0.45);
      fmt::print("{:<6} {:<34} {:>8} {:>9.2f} {:>9.2f} {:>9.2f} {:>8.2f}\n", model, v.name,
                 r.summary["nodes"]["final"].get<std::size_t>(), peak,
                 e.mean_ex(-0.4, -0.1), e.mean_ex(0.1, 0.4), e.l2);
      if (csv)
        for (std::size_t k = 0; k < e.x.size(); ++k)
          csv << fmt::format("{},{},{},{:.6g},{:.6g}\n", model, level, v.name, e.x[k], e.ex[k]);
      series.push_back({v.name, e.x, e.ex});
    }
    if (!out_dir.empty()) {
      PlotOptions po;
      po.title = fmt::format("Model {} (left half at level {}): error of u_x, horizontal centre line",
                             static_cast<char>('A' + level - 1), level);
      po.x_label = "x (m)";
      po.y_label = "error (%)";
      write_line_plot(fmt::format("{}/static_plate_refined_model_{}.png", out_dir,
                                  static_cast<char>('A' + level - 1)),
                      series, po);
    }
  }
  fmt::print("thesis (scaling & DH): peak about 31.5% in the coarse interface zone at every level; "
             "plateaus about 7% (refined) and 5% (coarse); with surface correction 1.5% and 2%\n");
  return 0;
}

}  // namespace periadapt
