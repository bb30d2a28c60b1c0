#include "studies/static_plate_2d.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/static_run.hpp"
#include "io/deck.hpp"
#include "io/line_plot.hpp"

namespace periadapt {

namespace {

const char* kDeck = R"(
model: {dimension: 2, plane: stress, thickness: 0.01}
material: {youngs_modulus: 200.0e9, density: 7850.0}
discretization:
  spacing: 0.01
  horizon: 0.03015
  registration: node_on_edge
  quadrature: ipa_hybrid
  surface_correction: SC
  body: {box: {min: [-0.5, -0.25], max: [0.5, 0.25]}}
loads:
  - {name: right, type: traction, region: {box: {min: [0.5, -0.25], max: [0.5, 0.25]}}, value: [200.0e6, 0]}
  - {name: left, type: traction, region: {box: {min: [-0.5, -0.25], max: [-0.5, 0.25]}}, value: [-200.0e6, 0]}
boundary_conditions:
  - {name: vertical axis, region: {box: {min: [0, -0.25], max: [0, 0.25]}}, displacement: [0, null]}
  - {name: horizontal axis, region: {box: {min: [-0.5, 0], max: [0.5, 0]}}, displacement: [null, 0]}
damage: {enabled: false}
solver: {type: static}
)";

struct Profiles {
  std::vector<double> x, ex, y, ey;  // positions and relative errors (%)
  double mean_ex = 0, mean_ey = 0, l2 = 0;
};

Profiles solve(bool correction) {
  std::string text = kDeck;
  text.replace(text.find("SC"), 2, correction ? "true" : "false");
  const Deck dk = parse_deck(text, "static-plate-2d (built-in)");
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  const RunResult r = run_static(dk, ro);
  const NodeSet& ns = r.model.nodes;
  const double E = 200e9, s = 200e6, nu = 1.0 / 3.0, tol = 1e-9;
  Profiles p;
  double num = 0, den = 0;
  std::vector<std::pair<double, double>> hx, vy;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const double X = ns.x[0][i], Y = ns.x[1][i];
    const double ux = s * X / E, uy = -nu * s * Y / E;
    num += std::pow(ns.u[0][i] - ux, 2) + std::pow(ns.u[1][i] - uy, 2);
    den += ux * ux + uy * uy;
    // Profiles on the positive half-axes, the constrained node at the origin excluded.
    if (std::abs(Y) < tol && X > tol) hx.emplace_back(X, 100 * std::abs(ns.u[0][i] - ux) / std::abs(ux));
    if (std::abs(X) < tol && Y > tol) vy.emplace_back(Y, 100 * std::abs(ns.u[1][i] - uy) / std::abs(uy));
  }
  std::sort(hx.begin(), hx.end());
  std::sort(vy.begin(), vy.end());
  for (auto [a, e] : hx) p.x.push_back(a), p.ex.push_back(e), p.mean_ex += e / hx.size();
  for (auto [a, e] : vy) p.y.push_back(a), p.ey.push_back(e), p.mean_ey += e / vy.size();
  p.l2 = 100 * std::sqrt(num / den);
  return p;
}

}  // namespace

int run_static_plate_study(const std::string& out_dir) {
  const Profiles plain = solve(false), corrected = solve(true);
  fmt::print("Thesis 4.1, uniform grid (dX = 10 mm, delta = 30.15 mm, IPA-Hybrid areas): errors vs "
             "Eq. 4.1\n");
  fmt::print("{:<26} {:>16} {:>16} {:>12}\n", "", "mean |e(u_x)| %", "mean |e(u_y)| %", "L2 (Eq 4.2) %");
  fmt::print("{:<26} {:>16.3f} {:>16.3f} {:>12.3f}   (thesis: about 5% on the coarse side)\n",
             "no surface correction", plain.mean_ex, plain.mean_ey, plain.l2);
  fmt::print("{:<26} {:>16.3f} {:>16.3f} {:>12.3f}   (thesis: about 2%)\n",
             "surface correction", corrected.mean_ex, corrected.mean_ey, corrected.l2);
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
