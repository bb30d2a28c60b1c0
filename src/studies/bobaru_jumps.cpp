#include "studies/bobaru_jumps.hpp"

#include <fmt/core.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>

#include "studies/study_csv.hpp"

namespace periadapt {

namespace {

// Least-squares quadratic through the nodes with x0 + lo <= x <= x0 + hi, evaluated at x0.
double one_sided_limit(const BarSolution& bar, double x0, double lo, double hi) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < bar.x.size(); ++k) {
    const double t = bar.x[k] - x0;
    if (t < lo || t > hi) continue;
    const Eigen::Vector3d p(1.0, t, t * t);
    A += p * p.transpose();
    r += p * bar.u[k];
  }
  return A.ldlt().solve(r)[0];
}

}  // namespace

BarJumps measure_bar_jumps(const BarSolution& bar, double a, double delta, double dx) {
  const double g = 2 * dx, w = 0.3 * delta;
  auto jump = [&](double x0) {
    return one_sided_limit(bar, x0, g, w) - one_sided_limit(bar, x0, -w, -g);
  };
  BarJumps j;
  j.jump_left = jump(delta - a);
  j.jump_right = jump(delta + a);
  std::size_t ka = 0;
  for (std::size_t k = 0; k < bar.x.size(); ++k)
    if (std::abs(bar.x[k] - a) < std::abs(bar.x[ka] - a)) ka = k;
  j.spike = bar.u[ka] - 0.5 * (one_sided_limit(bar, a, g, w) + one_sided_limit(bar, a, -w, -g));
  return j;
}

int run_bobaru_jumps_study(const std::string& out_dir) {
  std::ofstream csv = open_study_csv(out_dir, "bobaru_jumps.csv",
                                     "sweep,delta,m,jump_left,jump_right,delta_over_12,spike,eq34");
  fmt::print("Bobaru et al. 2009, 3.2: inverted-triangle micromodulus, unit loads at -+1 on a bar of "
             "length 4, E = 1. [u] at delta - a and delta + a against +-delta/12 (Eqs. 32-33); the "
             "load node's spike against delta^2/(6 dx) (Eq. 34)\n");
  fmt::print("{:>7} {:>6} {:>5} | {:>10} {:>10} {:>10} {:>7} | {:>10} {:>10} {:>7}\n", "sweep", "delta",
             "m", "[u] d-a", "[u] d+a", "delta/12", "err %", "spike", "Eq. 34", "err %");
  struct Case {
    const char* sweep;
    double delta, m;
  };
  // m-convergence (delta fixed): conclusion (i), the jumps and the spike are resolved; delta-
  // convergence at fixed m: conclusion (iii), both vanish with delta.
  const Case cases[] = {{"m", 0.2, 20},    {"m", 0.2, 40},    {"m", 0.2, 80},  {"m", 0.2, 160},
                        {"delta", 0.4, 40}, {"delta", 0.1, 40}, {"delta", 0.05, 40}};
  for (const Case& c : cases) {
    BarSpec s;
    s.length = 4.0;
    s.m = c.m;
    s.dx = c.delta / c.m;
    s.shape = InfluenceShape::InvertedTriangular;
    const BarSolution bar = solve_bobaru_bar(s);
    const BarJumps j = measure_bar_jumps(bar, s.a, c.delta, s.dx);
    const double exact = c.delta / 12, eq34 = c.delta * c.delta / (6 * s.dx);
    const double err = 100 * std::max(std::abs(j.jump_left - exact), std::abs(j.jump_right + exact)) / exact;
    fmt::print("{:>7} {:>6.3f} {:>5.0f} | {:>+10.6f} {:>+10.6f} {:>10.6f} {:>7.2f} | {:>10.5f} {:>10.5f} {:>7.3f}\n",
               c.sweep, c.delta, c.m, j.jump_left, j.jump_right, exact, err, j.spike, eq34,
               100 * (j.spike - eq34) / eq34);
    if (csv)
      csv << fmt::format("{},{},{},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g}\n", c.sweep, c.delta, c.m,
                         j.jump_left, j.jump_right, exact, j.spike, eq34);
  }
  return 0;
}

}  // namespace periadapt
