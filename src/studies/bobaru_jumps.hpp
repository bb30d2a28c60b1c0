#pragma once
// Bobaru et al. (2009) 3.2: the static bar of sections 2-5 with the inverted-triangle
// micromodulus (constant spring stiffness C = 3E/delta^3). The peridynamic solution for point
// loads +-b0 at +-a has a Dirac component at each load, of weight delta^2 b0 / (6E) (Eq. 29),
// which a grid resolves as a spike of delta^2 b0 / (6E dx) at the load node (Eq. 34), and finite
// jumps [u] = +delta/(12E) at x = delta - a and -delta/(12E) at x = delta + a (Eqs. 32-33).
#include <string>

#include "studies/bobaru_1d_static.hpp"

namespace periadapt {

struct BarJumps {
  double jump_left = 0;   // [u] at x = delta - a
  double jump_right = 0;  // [u] at x = delta + a
  double spike = 0;       // u at the load node x = a less the smooth field there
};

// Jumps of a solved bar: one-sided quadratic fits over (2 dx, 0.3 delta) from each side,
// evaluated at the point (the smooth parts vary on the scale of delta).
BarJumps measure_bar_jumps(const BarSolution& bar, double a, double delta, double dx);

int run_bobaru_jumps_study(const std::string& out_dir);

}  // namespace periadapt
