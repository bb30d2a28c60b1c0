#pragma once
// Peridynamic differential operator (Madenci et al. 2016), zeroth order with a quadratic basis
// (Stewart & Jeon 2019, Eqs. 8-10): the value of a field at any point x from the values at nearby
// material points k,  f(x) = sum_k f_k g(xi_k) V_k,  xi_k = x_k - x,
//   g(xi) = w(|xi|) sum_q a_q P_q(xi),  P = {1, x, y, (z), x^2, xy, (xz), y^2, (yz), (z^2)},
// with the a_q from the moment conditions sum_k w P_q P_r V_k a_r = [q == 0]. Exact for every
// quadratic field. The weight w(r) is left open by the paper ("identical for every term"):
// uniform (w = 1 within the sample set) or Gaussian, w(r) = exp(-(2 r / delta)^2) (Madenci's).
#include <array>
#include <cstdint>
#include <vector>

namespace periadapt {

enum class PddoWeight { Uniform, Gaussian };

struct PddoPoint {
  std::array<double, 3> x;  // material point position
  double volume;
};

// Weights c_k such that f(x) = sum_k c_k f_k for the given points (dim 1, 2 or 3); false when the
// moment matrix is singular (too few or degenerate points).
bool pddo_weights(int dim, const std::array<double, 3>& at, const std::vector<PddoPoint>& pts,
                  double delta, std::vector<double>& c,
                  PddoWeight weight = PddoWeight::Uniform);

}  // namespace periadapt
