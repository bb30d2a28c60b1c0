#include "studies/static_plate_2d.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/static_run.hpp"
#include "io/deck.hpp"
#include "io/line_plot.hpp"
#include "studies/plate_error_profiles.hpp"

namespace periadapt {

namespace {


double mean(const std::vector<double>& v) {
  double s = 0;
  for (double e : v) s += e;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

PlateErrors solve(bool correction) {
  const Deck dk =
      parse_deck(tension_plate_deck(correction, "source_horizon", 0), "static-plate-2d (built-in)");
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  const RunResult r = run_static(dk, ro);
  return plate_errors(r.model.nodes, 200e6, 200e9, 1.0 / 3.0);
}

}  // namespace

int run_static_plate_study(const std::string& out_dir) {
  const PlateErrors plain = solve(false), corrected = solve(true);
  fmt::print("Thesis 4.1, uniform grid (dX = 10 mm, delta = 30.15 mm, IPA-Hybrid areas): errors vs "
             "Eq. 4.1\n");
  fmt::print("{:<26} {:>16} {:>16} {:>12}\n", "", "mean |e(u_x)| %", "mean |e(u_y)| %", "L2 (Eq 4.2) %");
  fmt::print("{:<26} {:>16.3f} {:>16.3f} {:>12.3f}   (thesis: about 5% on the coarse side)\n",
             "no surface correction", plain.mean_ex(0, 1), mean(plain.ey), plain.l2);
  fmt::print("{:<26} {:>16.3f} {:>16.3f} {:>12.3f}   (thesis: about 2%)\n",
             "surface correction", corrected.mean_ex(0, 1), mean(corrected.ey), corrected.l2);
  if (out_dir.empty()) return 0;
  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/static_plate_2d_errors.csv");
  csv << "line,coordinate_m,error_pct_plain,error_pct_corrected\n";
  for (std::size_t k = 0; k < plain.x.size(); ++k)
    csv << fmt::format("horizontal_ux,{:.6g},{:.6g},{:.6g}\n", plain.x[k], plain.ex[k], corrected.ex[k]);
  for (std::size_t k = 0; k < plain.y.size(); ++k)
    csv << fmt::format("vertical_uy,{:.6g},{:.6g},{:.6g}\n", plain.y[k], plain.ey[k], corrected.ey[k]);
  PlotOptions po;
  po.title = "Static plate (thesis 4.1): relative error of u_x on the horizontal centre line";
  po.x_label = "x (m)";
  po.y_label = "error (%)";
  write_line_plot(out_dir + "/static_plate_2d_ux_error.png",
                  {{"no surface correction", plain.x, plain.ex},
                   {"surface correction", corrected.x, corrected.ex}},
                  po);
  po.title = "Static plate (thesis 4.1): relative error of u_y on the vertical centre line";
  po.x_label = "y (m)";
  write_line_plot(out_dir + "/static_plate_2d_uy_error.png",
                  {{"no surface correction", plain.y, plain.ey},
                   {"surface correction", corrected.y, corrected.ey}},
                  po);
  fmt::print("wrote {0}/static_plate_2d_errors.csv, {0}/static_plate_2d_ux_error.png, "
             "{0}/static_plate_2d_uy_error.png\n", out_dir);
  return 0;
}

}  // namespace periadapt
