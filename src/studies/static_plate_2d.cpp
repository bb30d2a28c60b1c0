#include "studies/static_plate_2d.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "run/static_run.hpp"
#include "input/deck.hpp"
#include "io/line_plot.hpp"
#include "studies/plate_error_profiles.hpp"

namespace periadapt {

namespace {


double mean(const std::vector<double>& v) {
  double s = 0;
  for (double e : v) s += e;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

PlateErrors solve(const std::string& correction) {
  const Deck dk = tension_plate_deck(correction, "source_horizon", 0, false,
                                           "static-plate-2d (built-in)");
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  const RunResult r = run_static(dk, ro);
  return plate_errors(r.model.nodes, 200e6, 200e9, 1.0 / 3.0);
}

}  // namespace

int run_static_plate_study(const std::string& out_dir) {
  struct Row {
    const char* label;
    const char* deck_value;
    const char* thesis;
    PlateErrors e;
  };
  Row rows[3] = {{"no surface correction", "false", "(thesis: about 5% on the coarse side)", {}},
                 {"energy method", "energy", "(thesis: about 2%)", {}},
                 {"moment matching", "moments", "(energy method extended to shear states)", {}}};
  for (Row& r : rows) r.e = solve(r.deck_value);
  fmt::print("Thesis 4.1, uniform grid (dX = 10 mm, delta = 30.15 mm, IPA-Hybrid areas): errors vs "
             "Eq. 4.1\n");
  fmt::print("{:<26} {:>16} {:>16} {:>12}\n", "surface correction", "mean |e(u_x)| %",
             "mean |e(u_y)| %", "L2 (Eq 4.2) %");
  for (const Row& r : rows)
    fmt::print("{:<26} {:>16.3f} {:>16.3f} {:>12.3f}   {}\n", r.label, r.e.mean_ex(0, 1),
               mean(r.e.ey), r.e.l2, r.thesis);
  if (out_dir.empty()) return 0;
  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/static_plate_2d_errors.csv");
  csv << "line,coordinate_m,error_pct_plain,error_pct_energy,error_pct_moments\n";
  for (std::size_t k = 0; k < rows[0].e.x.size(); ++k)
    csv << fmt::format("horizontal_ux,{:.6g},{:.6g},{:.6g},{:.6g}\n", rows[0].e.x[k],
                       rows[0].e.ex[k], rows[1].e.ex[k], rows[2].e.ex[k]);
  for (std::size_t k = 0; k < rows[0].e.y.size(); ++k)
    csv << fmt::format("vertical_uy,{:.6g},{:.6g},{:.6g},{:.6g}\n", rows[0].e.y[k],
                       rows[0].e.ey[k], rows[1].e.ey[k], rows[2].e.ey[k]);
  PlotOptions po;
  po.title = "Static plate (thesis 4.1): relative error of u_x on the horizontal centre line";
  po.x_label = "x (m)";
  po.y_label = "error (%)";
  std::vector<PlotSeries> sx, sy;
  for (const Row& r : rows) {
    sx.push_back({r.label, r.e.x, r.e.ex});
    sy.push_back({r.label, r.e.y, r.e.ey});
  }
  write_line_plot(out_dir + "/static_plate_2d_ux_error.png", sx, po);
  po.title = "Static plate (thesis 4.1): relative error of u_y on the vertical centre line";
  po.x_label = "y (m)";
  write_line_plot(out_dir + "/static_plate_2d_uy_error.png", sy, po);
  fmt::print("wrote {0}/static_plate_2d_errors.csv, {0}/static_plate_2d_ux_error.png, "
             "{0}/static_plate_2d_uy_error.png\n", out_dir);
  return 0;
}

}  // namespace periadapt
