#include "overlay/pddo.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace periadapt {

namespace {

// Quadratic monomials of xi in `dim` dimensions; returns their number.
int basis(int dim, const double* d, double* P) {
  int q = 0;
  P[q++] = 1.0;
  for (int a = 0; a < dim; ++a) P[q++] = d[a];
  for (int a = 0; a < dim; ++a)
    for (int b = a; b < dim; ++b) P[q++] = d[a] * d[b];
  return q;
}

}  // namespace

bool pddo_weights(int dim, const std::array<double, 3>& at, const std::vector<PddoPoint>& pts,
                  double delta, std::vector<double>& c, PddoWeight weight) {
  const int nb = dim == 1 ? 3 : dim == 2 ? 6 : 10;
  // Scale coordinates by delta so the moment matrix is well conditioned.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nb, nb);
  std::vector<double> P(static_cast<std::size_t>(pts.size()) * nb), w(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    double d[3] = {0, 0, 0}, r2 = 0;
    for (int a = 0; a < dim; ++a) {
      d[a] = (pts[k].x[static_cast<std::size_t>(a)] - at[static_cast<std::size_t>(a)]) / delta;
      r2 += d[a] * d[a];
    }
    w[k] = (weight == PddoWeight::Gaussian ? std::exp(-4.0 * r2) : 1.0) * pts[k].volume;
    double* p = &P[k * nb];
    basis(dim, d, p);
    for (int q = 0; q < nb; ++q)
      for (int r = 0; r < nb; ++r) A(q, r) += w[k] * p[q] * p[r];
  }
  Eigen::VectorXd e = Eigen::VectorXd::Zero(nb);
  e[0] = 1.0;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (lu.rank() < nb) return false;
  const Eigen::VectorXd a = lu.solve(e);
  c.assign(pts.size(), 0.0);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    double s = 0;
    for (int q = 0; q < nb; ++q) s += a[q] * P[k * nb + q];
    c[k] = w[k] * s;
  }
  return true;
}

}  // namespace periadapt
