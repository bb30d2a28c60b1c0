#include "discretize/surface_correction.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace periadapt {

namespace {

// The bond's energy weight for node i: influence x quadrature factor x volume x length, so that
// W_pd(eps) = c_i / 4 * sum_k weight_k (n.eps.n)^2.
double energy_weight(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                     std::size_t i, std::uint64_t k) {
  const double L = bf.length(k);
  return influence(shape, std::min(1.0, L / ns.horizon[i])) *
         std::abs(static_cast<double>(bf.beta[k])) * ns.volume[bf.neighbor[k]] * L;
}

void unit_direction(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::uint64_t k,
                    double* n) {
  const std::uint32_t j = bf.neighbor[k];
  const double L = bf.length(k);
  for (int d = 0; d < ns.dim; ++d) n[d] = (ns.x[d][j] - ns.x[d][i]) / L;
}

void energy_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M) {
  const int D = ns.dim;
  const std::size_t n = ns.size();
  std::vector<double> g(3 * n, 1.0);
  const double w_classical = 0.5 * M;  // unit strain
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    double w[3] = {0, 0, 0};
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      double nv[3];
      unit_direction(ns, bf, i, k, nv);
      const double wt = energy_weight(ns, bf, shape, i, k);
      for (int d = 0; d < D; ++d) w[d] += wt * nv[d] * nv[d] * nv[d] * nv[d];
    }
    for (int d = 0; d < D; ++d) {
      const double wpd = 0.25 * ns.micromodulus[i] * w[d];
      g[3 * i + d] = wpd > 0 ? w_classical / wpd : 1.0;
    }
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      double nv[3], q = 0;
      unit_direction(ns, bf, i, k, nv);
      for (int d = 0; d < D; ++d) {
        const double gbar = 0.5 * (g[3 * i + d] + g[3 * j + d]);
        q += (nv[d] / gbar) * (nv[d] / gbar);
      }
      bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) / std::sqrt(q));
    }
  }
}

// Basis of the direction functions and of the matched moments: n_d^2 n_d^2 and n_d^2 n_e^2
// (d < e) for the moments; n_d^2 and n_d^2 n_e^2 for G. Both have D (D + 1) / 2 entries.
int term_count(int D) { return D * (D + 1) / 2; }

void direction_terms(int D, const double* n, double* g_basis, double* moment_basis) {
  int t = 0;
  for (int d = 0; d < D; ++d, ++t) {
    g_basis[t] = n[d] * n[d];
    moment_basis[t] = g_basis[t] * g_basis[t];
  }
  for (int d = 0; d < D; ++d)
    for (int e = d + 1; e < D; ++e, ++t) {
      g_basis[t] = n[d] * n[d] * n[e] * n[e];
      moment_basis[t] = g_basis[t];
    }
}

void moment_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M) {
  const int D = ns.dim;
  const int T = term_count(D);
  const std::size_t n = ns.size();
  std::vector<double> p(static_cast<std::size_t>(T) * n);
  // Each sweep fits every node's own multiplier G_i(n) to its current moments, then multiplies
  // each bond by sqrt(G_i(n) G_j(n)); at the fixed point every multiplier is 1 and every node
  // has the bulk moments with symmetric bond factors. The geometric mean keeps the factors
  // positive and lets a node next to the surface offset a large factor of its neighbour. The
  // plain geometric mean is an under-relaxed step (each end asks for its whole correction);
  // over-relaxing by 1.6 halves the sweeps of a surface layer (linear convergence either way).
  constexpr int kSweeps = 100;
  constexpr double kRelaxation = 1.6, kTolerance = 1e-5;  // tolerance: largest bond update
  constexpr double kMinStep = 0.5, kMaxStep = 2.0;  // per-sweep multiplier range, for stability
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      for (int t = 0; t < T; ++t) p[T * i + t] = t < D ? 1.0 : 0.0;
      if (!(ns.flags[i] & kActive)) continue;
      Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
      // Bulk moments: W = c/4 sum w (n.eps.n)^2 = M eps^2 / 2 under uniaxial strain, and the
      // isotropic ratio sum n_x^4 : sum n_x^2 n_y^2 = 3 : 1 (2D and 3D alike).
      const double axial = 2.0 * M / ns.micromodulus[i];
      for (int t = 0; t < T; ++t) r(t) = t < D ? axial : axial / 3.0;
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        double nv[3], gb[6], mb[6];
        unit_direction(ns, bf, i, k, nv);
        direction_terms(D, nv, gb, mb);
        const double wt = energy_weight(ns, bf, shape, i, k);
        for (int a = 0; a < T; ++a)
          for (int b = 0; b < T; ++b) A(a, b) += wt * mb[a] * gb[b];
      }
      const auto lu = A.topLeftCorner(T, T).fullPivLu();
      if (!lu.isInvertible()) continue;  // degenerate family (a lone corner node): G = 1
      const Eigen::VectorXd sol = lu.solve(r.head(T));
      for (int t = 0; t < T; ++t) p[T * i + t] = sol(t);
    }
    double worst = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : worst)
    for (std::size_t i = 0; i < n; ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        const std::uint32_t j = bf.neighbor[k];
        double nv[3], gb[6], mb[6], gi = 0, gj = 0;
        unit_direction(ns, bf, i, k, nv);
        direction_terms(D, nv, gb, mb);
        for (int t = 0; t < T; ++t) gi += p[T * i + t] * gb[t], gj += p[T * j + t] * gb[t];
        gi = std::clamp(gi, kMinStep, kMaxStep);
        gj = std::clamp(gj, kMinStep, kMaxStep);
        const double g = std::pow(gi * gj, 0.5 * kRelaxation);
        worst = std::max(worst, std::abs(g - 1));
        bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) * g);
      }
    }
    if (worst < kTolerance) break;
  }
}

}  // namespace

void apply_surface_correction(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                              SurfaceCorrection method) {
  if (method == SurfaceCorrection::None) return;
  if (method == SurfaceCorrection::Moments && ns.dim > 1)
    moment_method(ns, bf, shape, M);
  else
    energy_method(ns, bf, shape, M);
}

}  // namespace periadapt
