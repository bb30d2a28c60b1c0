#include "discretize/interface_quadrature.hpp"

#include <Eigen/Dense>
#include <array>
#include <initializer_list>
#include <cmath>
#include <vector>

#include "core/cell_grid.hpp"

namespace periadapt {

namespace {

// The cubic monomials e_p e_q e_r, p <= q <= r, of a unit direction in `dim` dimensions.
int cubic_monomials(int dim, const double e[3], double* phi) {
  int n = 0;
  for (int p = 0; p < dim; ++p)
    for (int q = p; q < dim; ++q)
      for (int r = q; r < dim; ++r) phi[n++] = e[p] * e[q] * e[r];
  return n;
}

// Unit directions for sampling a ball: sparse (16 in 2D, the 26 lattice directions in 3D) or
// dense (32 in 2D, 64 on a Fibonacci sphere in 3D); both ways in 1D.
std::vector<std::array<double, 3>> sample_directions(int D, bool dense) {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<std::array<double, 3>> dirs;
  if (D == 1) {
    dirs = {{1, 0, 0}, {-1, 0, 0}};
  } else if (D == 2) {
    const int n = dense ? 32 : 16;
    const double shift = dense ? 0.5 : 0.0;
    for (int a = 0; a < n; ++a) {
      const double t = 2 * kPi * (a + shift) / n;
      dirs.push_back({std::cos(t), std::sin(t), 0});
    }
  } else if (dense) {
    const double golden = kPi * (3 - std::sqrt(5.0));
    for (int k = 0; k < 64; ++k) {
      const double z = 1 - 2 * (k + 0.5) / 64, r = std::sqrt(1 - z * z);
      dirs.push_back({r * std::cos(golden * k), r * std::sin(golden * k), z});
    }
  } else {
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z) {
          const double n = std::sqrt(static_cast<double>(x * x + y * y + z * z));
          if (n > 0) dirs.push_back({x / n, y / n, z / n});
        }
  }
  return dirs;
}

// Whether the nodes' cells cover i's ball, sampled in `dirs` at the given fractions of its
// horizon: a free surface, hole or body edge within them leaves a sample uncovered. Only the
// nodes are read, so any body geometry works.
bool ball_covered(const NodeSet& ns, const CellGrid& grid, double reach, std::size_t i,
                  const std::vector<std::array<double, 3>>& dirs, std::initializer_list<double> radii) {
  const int D = ns.dim;
  for (const double f : radii)
    for (const auto& e : dirs) {
      std::array<double, 3> p{0, 0, 0};
      for (int d = 0; d < D; ++d) p[d] = ns.x[d][i] + f * ns.horizon[i] * e[d];
      bool covered = false;
      grid.for_each_within(p, reach, [&](std::uint32_t j, double) {
        double far = 0;
        for (int d = 0; d < D; ++d) far = std::max(far, std::abs(p[d] - ns.x[d][j]));
        covered = covered || far <= 0.5 * ns.spacing[j] * (1 + 1e-9);
      });
      if (!covered) return false;
    }
  return true;
}

// The active nodes whose cells a sample around `rows` can meet (within the rows' box grown by
// their largest horizon and two query reaches), and the reach: a cell covers a point within half
// its spacing per axis, so within sqrt(D)/2 of the largest spacing.
std::vector<std::uint32_t> nodes_around(const NodeSet& ns, const std::vector<std::uint32_t>& rows,
                                        double& reach) {
  const int D = ns.dim;
  double smax = 0, hmax = 0, lo[3] = {INFINITY, INFINITY, INFINITY},
         hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) smax = std::max(smax, ns.spacing[i]);
  for (std::uint32_t i : rows) {
    hmax = std::max(hmax, ns.horizon[i]);
    for (int d = 0; d < D; ++d) lo[d] = std::min(lo[d], ns.x[d][i]), hi[d] = std::max(hi[d], ns.x[d][i]);
  }
  reach = 0.5 * std::sqrt(static_cast<double>(D)) * smax * (1 + 1e-9);
  std::vector<std::uint32_t> near;
  for (std::size_t j = 0; j < ns.size(); ++j) {
    if (!(ns.flags[j] & kActive)) continue;
    bool in = true;
    for (int d = 0; d < D && in; ++d)
      in = ns.x[d][j] >= lo[d] - hmax - 2 * reach && ns.x[d][j] <= hi[d] + hmax + 2 * reach;
    if (in) near.push_back(static_cast<std::uint32_t>(j));
  }
  return near;
}

}  // namespace

InterfaceFitStats fit_interface_quadrature(const NodeSet& ns, BondFamilies& bf,
                                           InfluenceShape shape, const std::vector<char>& rows) {
  InterfaceFitStats st;
  const int D = ns.dim;
  std::vector<std::uint32_t> todo;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && (rows.empty() || rows[i])) todo.push_back(static_cast<std::uint32_t>(i));
  if (todo.empty()) return st;
  double reach = 0;
  const std::vector<std::uint32_t> near = nodes_around(ns, todo, reach);
  const CellGrid grid(D, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, near, reach);
  const std::vector<std::array<double, 3>> dirs = sample_directions(D, false);
  enum Outcome : std::uint8_t { kSkip, kIncomplete, kRefused, kFitted };
  // One row; rows are independent (each scales its own bonds).
  auto fit_row = [&](std::size_t i) -> Outcome {
    // Cells of another size within the horizon, in the family or not (a coarse cell partly inside
    // a fine node's horizon whose centre lies beyond it leaves the family lopsided).
    bool mixed = false, cut = false;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      mixed = mixed || ns.spacing[bf.neighbor[k]] != ns.spacing[i];
      cut = cut || !BondFamilies::intact(bf.beta[k]);
    }
    if (!mixed)
      grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, ns.horizon[i] + reach,
                           [&](std::uint32_t j, double) {
                             mixed = mixed || ns.spacing[j] != ns.spacing[i];
                           });
    if (!mixed) return kSkip;
    if (cut || !ball_covered(ns, grid, reach, i, dirs, {0.8})) return kIncomplete;
    constexpr int kMax = 10;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax> M;
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> t;
    int nm = 0;
    auto monomials = [&](std::uint64_t k, double* phi) {
      const std::uint32_t j = bf.neighbor[k];
      const double len = 1.0 / std::abs(bf.inv_length[k]);
      double e[3] = {0, 0, 0};
      for (int d = 0; d < D; ++d) e[d] = (ns.x[d][j] - ns.x[d][i]) / len;
      return cubic_monomials(D, e, phi);
    };
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      double phi[kMax];
      nm = monomials(k, phi);
      if (M.rows() == 0) {
        M.setZero(nm, nm);
        t.setZero(nm);
      }
      const double len = 1.0 / std::abs(bf.inv_length[k]);
      const double w = influence(shape, std::min(1.0, len / ns.horizon[i])) *
                       static_cast<double>(bf.beta[k]) * ns.volume[bf.neighbor[k]];
      for (int a = 0; a < nm; ++a) {
        t[a] += w * phi[a];
        for (int b = 0; b < nm; ++b) M(a, b) += w * phi[a] * phi[b];
      }
    }
    if (nm == 0) return kSkip;
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> lambda = M.ldlt().solve(-t);
    // Each bond's factor; a fit that needs large ones is not a small quadrature repair.
    std::vector<double> factor;
    if (!lambda.allFinite()) return kRefused;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      double phi[kMax];
      monomials(k, phi);
      double f = 1;
      for (int a = 0; a < nm; ++a) f += lambda[a] * phi[a];
      if (!(f >= 0.5 && f <= 1.5)) return kRefused;
      factor.push_back(f);
    }
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
      bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) * factor[k - bf.begin(i)]);
    return kFitted;
  };
  std::vector<Outcome> outcome(todo.size(), kSkip);
#pragma omp parallel for schedule(dynamic, 32)
  for (std::size_t q = 0; q < todo.size(); ++q) outcome[q] = fit_row(todo[q]);
  for (Outcome o : outcome) {
    st.interface_rows += o != kSkip;
    st.incomplete += o == kIncomplete;
    st.refused += o == kRefused;
    st.fitted += o == kFitted;
  }
  return st;
}

std::vector<char> rows_with_covered_ball(const NodeSet& ns, const std::vector<std::uint32_t>& rows) {
  std::vector<char> out(rows.size(), 0);
  if (rows.empty()) return out;
  double reach = 0;
  const std::vector<std::uint32_t> near = nodes_around(ns, rows, reach);
  const CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, near, reach);
  // Rings at 0.5, 0.8 and 0.98 of the horizon, so a surface anywhere within it is seen.
  const std::vector<std::array<double, 3>> dirs = sample_directions(ns.dim, true);
#pragma omp parallel for schedule(dynamic, 32)
  for (std::size_t q = 0; q < rows.size(); ++q)
    out[q] = ball_covered(ns, grid, reach, rows[q], dirs, {0.5, 0.8, 0.98});
  return out;
}

}  // namespace periadapt
