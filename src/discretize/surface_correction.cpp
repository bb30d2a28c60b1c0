#include "discretize/surface_correction.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace periadapt {

namespace {

// The bond's energy weight for node i: influence x quadrature factor x volume x length, so that
// W_pd(eps) = c_i / 4 * sum_k weight_k (n.eps.n)^2.
// State-based (LPS): the weight of the bond in the node's weighted volume m and in its
// second and fourth moments, one length more.
double energy_weight(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                     std::size_t i, std::uint64_t k, bool state_based = false) {
  const double L = bf.length(k);
  return influence(shape, std::min(1.0, L / ns.horizon[i])) *
         std::abs(static_cast<double>(bf.beta[k])) * ns.volume[bf.neighbor[k]] * L *
         (state_based ? L : 1.0);
}

void unit_direction(const NodeSet& ns, const BondFamilies& bf, std::size_t i, std::uint64_t k,
                    double* n) {
  const std::uint32_t j = bf.neighbor[k];
  const double L = bf.length(k);
  for (int d = 0; d < ns.dim; ++d) n[d] = (ns.x[d][j] - ns.x[d][i]) / L;
}

// The uniaxial modulus of node i: M, or its block's.
double node_modulus(const NodeSet& ns, double M, const std::vector<double>& block_modulus,
                    std::size_t i) {
  return block_modulus.empty() ? M : block_modulus[ns.block[i]];
}

void energy_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                   const std::vector<double>& block_modulus) {
  const int D = ns.dim;
  const std::size_t n = ns.size();
  std::vector<double> g(3 * n, 1.0);
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
    const double w_classical = 0.5 * node_modulus(ns, M, block_modulus, i);  // unit strain
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

// Basis of the direction functions G and of the matched moments. Bond-based: n_d^2 n_d^2 and
// n_d^2 n_e^2 (d < e) for the moments, n_d^2 and n_d^2 n_e^2 for G, D (D + 1) / 2 entries.
// State-based: every fourth-order monomial n_x^a n_y^b n_z^c (a + b + c = 4; 5 in 2D, 15 in 3D)
// for both, so that the odd moments the neighbours' factors leave in a node's family (a node
// beside a corner region) are matched too; they set the dilatation of a shear.
struct MomentBasis {
  int D;
  bool full;
  std::vector<std::array<int, 3>> monomials;
  MomentBasis(int dim, bool state_based) : D(dim), full(state_based) {
    if (!full) return;
    for (int a = 4; a >= 0; --a)
      for (int b = 4 - a; b >= 0; --b) {
        const int c = 4 - a - b;
        if ((D < 3 && c > 0) || (D < 2 && b > 0)) continue;
        monomials.push_back({a, b, c});
      }
  }
  int size() const { return full ? static_cast<int>(monomials.size()) : D * (D + 1) / 2; }
  int index_of(int a, int b, int c) const {
    for (std::size_t t = 0; t < monomials.size(); ++t)
      if (monomials[t] == std::array<int, 3>{a, b, c}) return static_cast<int>(t);
    return -1;
  }
  // The bond-based basis' coefficients in the full one: n_d^2 = n_d^2 (n.n).
  void reduced_to_full(const double* reduced, double* out) const {
    std::fill(out, out + size(), 0.0);
    auto mono = [&](int d, int pd, int e, int pe) {
      int ex[3] = {0, 0, 0};
      ex[d] += pd;
      ex[e] += pe;
      return index_of(ex[0], ex[1], ex[2]);
    };
    int t = 0;
    for (int d = 0; d < D; ++d, ++t) {
      out[mono(d, 4, d, 0)] += reduced[t];
      for (int e = 0; e < D; ++e)
        if (e != d) out[mono(d, 2, e, 2)] += reduced[t];
    }
    for (int d = 0; d < D; ++d)
      for (int e = d + 1; e < D; ++e, ++t) out[mono(d, 2, e, 2)] += reduced[t];
  }
  // Coefficients of G = 1: (n.n)^2 = sum n_d^4 + 2 sum_{d<e} n_d^2 n_e^2.
  double identity(int t) const {
    if (!full) return t < D ? 1.0 : 0.0;
    const auto& e = monomials[t];
    if (e[0] % 2 || e[1] % 2 || e[2] % 2) return 0.0;
    return (e[0] == 4 || e[1] == 4 || e[2] == 4) ? 1.0 : 2.0;
  }
  // Isotropic moments: sum w n^4 terms of c (d_ab d_cd + d_ac d_bd + d_ad d_bc), with `axial`
  // = the n_d^4 moment 3c.
  double target(int t, double axial) const {
    if (!full) return t < D ? axial : axial / 3.0;
    const auto& e = monomials[t];
    if (e[0] % 2 || e[1] % 2 || e[2] % 2) return 0.0;
    return (e[0] == 4 || e[1] == 4 || e[2] == 4) ? axial : axial / 3.0;
  }
  void terms(const double* n, double* g_basis, double* moment_basis) const {
    if (full) {
      for (int t = 0; t < size(); ++t) {
        const auto& e = monomials[t];
        double v = 1;
        for (int d = 0; d < D; ++d)
          for (int k = 0; k < e[d]; ++k) v *= n[d];
        g_basis[t] = moment_basis[t] = v;
      }
      return;
    }
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
};

void moment_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                   const std::vector<double>& block_modulus,
                   bool state_based) {
  const int D = ns.dim;
  const MomentBasis basis(D, state_based);
  const int T = basis.size();
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
      for (int t = 0; t < T; ++t) p[T * i + t] = basis.identity(t);
      if (!(ns.flags[i] & kActive)) continue;
      // Bulk moments: W = c/4 sum w (n.eps.n)^2 = M eps^2 / 2 under uniaxial strain, and the
      // isotropic ratio sum n_x^4 : sum n_x^2 n_y^2 = 3 : 1 (2D and 3D alike).
      // State-based: the state is normalized by m = sum w x^2 V, so only the moments relative
      // to m count; isotropic ones (sum n_x^4 = 3 m / (D (D + 2)), sum n_x^2 n_y^2 = m / (D (D +
      // 2)), odd ones 0) give the exact dilatation and the classical energy of every homogeneous
      // strain.
      const auto fit = [&](const MomentBasis& b, double* sol) {
        const int Tb = b.size();
        Eigen::Matrix<double, 15, 15> A = Eigen::Matrix<double, 15, 15>::Zero();
        Eigen::Matrix<double, 15, 1> r = Eigen::Matrix<double, 15, 1>::Zero();
        double axial = 2.0 * node_modulus(ns, M, block_modulus, i) / ns.micromodulus[i], m_i = 0;
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
          double nv[3], gb[15], mb[15];
          unit_direction(ns, bf, i, k, nv);
          b.terms(nv, gb, mb);
          const double wt = energy_weight(ns, bf, shape, i, k, state_based);
          m_i += wt;
          for (int a = 0; a < Tb; ++a)
            for (int c = 0; c < Tb; ++c) A(a, c) += wt * mb[a] * gb[c];
        }
        if (state_based) axial = 3.0 * m_i / (D * (D + 2));
        for (int t = 0; t < Tb; ++t) r(t) = b.target(t, axial);
        const auto lu = A.topLeftCorner(Tb, Tb).fullPivLu();
        if (!lu.isInvertible()) return false;  // degenerate family (a lone corner node): G = 1
        const Eigen::VectorXd x = lu.solve(r.head(Tb));
        for (int t = 0; t < Tb; ++t) sol[t] = x(t);
        return true;
      };
      double sol[15];
      if (!fit(basis, sol)) continue;
      if (basis.full) {
        // A family that covers too few directions (a corner's) has no isotropic weighting with
        // positive factors: its fit turns negative somewhere. Such a node matches only the axis
        // moments, as the bond-based basis does.
        double lowest = INFINITY;
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
          double nv[3], gb[15], mb[15], g = 0;
          unit_direction(ns, bf, i, k, nv);
          basis.terms(nv, gb, mb);
          for (int t = 0; t < T; ++t) g += sol[t] * gb[t];
          lowest = std::min(lowest, g);
        }
        if (lowest < kMinStep) {
          const MomentBasis reduced(D, false);
          double rs[15];
          if (!fit(reduced, rs)) continue;
          basis.reduced_to_full(rs, sol);
        }
      }
      for (int t = 0; t < T; ++t) p[T * i + t] = sol[t];
    }
    double worst = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : worst)
    for (std::size_t i = 0; i < n; ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        const std::uint32_t j = bf.neighbor[k];
        double nv[3], gb[15], mb[15], gi = 0, gj = 0;
        unit_direction(ns, bf, i, k, nv);
        basis.terms(nv, gb, mb);
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
                              SurfaceCorrection method, bool state_based,
                              const std::vector<double>& block_modulus) {
  if (method == SurfaceCorrection::None) return;
  if (method == SurfaceCorrection::Moments && ns.dim > 1)
    moment_method(ns, bf, shape, M, block_modulus, state_based);
  else
    energy_method(ns, bf, shape, M, block_modulus);
}

}  // namespace periadapt
