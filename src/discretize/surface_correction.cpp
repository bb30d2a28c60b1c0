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
double bond_weight(InfluenceShape shape, double L, double delta_i, double beta, double volume_j,
                   bool state_based) {
  return influence(shape, std::min(1.0, L / delta_i)) * std::abs(beta) * volume_j * L *
         (state_based ? L : 1.0);
}

double energy_weight(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                     std::size_t i, std::uint64_t k, bool state_based = false) {
  return bond_weight(shape, bf.length(k), ns.horizon[i], static_cast<double>(bf.beta[k]),
                     ns.volume[bf.neighbor[k]], state_based);
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

// The energy method's per-node factors g_d (the classical over the peridynamic energy of a unit
// uniaxial strain along axis d) from a family's bonds, given as (neighbour, length, beta).
template <class Bonds>
void energy_factors(const NodeSet& ns, InfluenceShape shape, double M,
                    const std::vector<double>& block_modulus, std::size_t i, Bonds&& bonds,
                    double* g) {
  const int D = ns.dim;
  double w[3] = {0, 0, 0};
  bonds([&](std::uint32_t j, double L, double beta) {
    const double wt = bond_weight(shape, L, ns.horizon[i], beta, ns.volume[j], false);
    for (int d = 0; d < D; ++d) {
      const double nd = (ns.x[d][j] - ns.x[d][i]) / L;
      w[d] += wt * nd * nd * nd * nd;
    }
  });
  const double w_classical = 0.5 * node_modulus(ns, M, block_modulus, i);  // unit strain
  for (int d = 0; d < D; ++d) {
    const double wpd = 0.25 * ns.micromodulus[i] * w[d];
    g[d] = wpd > 0 ? w_classical / wpd : 1.0;
  }
  for (int d = D; d < 3; ++d) g[d] = 1.0;
}

// The energy method divides a bond's factor by this, from its two ends' g.
double energy_bond_divisor(const NodeSet& ns, std::size_t i, std::uint32_t j, double L,
                          const double* gi, const double* gj) {
  double q = 0;
  for (int d = 0; d < ns.dim; ++d) {
    const double nd = (ns.x[d][j] - ns.x[d][i]) / L;
    const double gbar = 0.5 * (gi[d] + gj[d]);
    q += (nd / gbar) * (nd / gbar);
  }
  return std::sqrt(q);
}

template <class F>
void row_bonds(const BondFamilies& bf, std::size_t i, F&& f) {
  for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
    f(bf.neighbor[k], bf.length(k), static_cast<double>(bf.beta[k]));
}

void energy_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                   const std::vector<double>& block_modulus, const HeldRowsShare* held) {
  const std::size_t n = ns.size();
  std::vector<double> g(3 * n, 1.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    energy_factors(ns, shape, M, block_modulus, i,
                   [&](auto&& visit) { row_bonds(bf, i, visit); }, &g[3 * i]);
  }
  if (held) held->owners(g, 3);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) /
                                      energy_bond_divisor(ns, i, j, bf.length(k), &g[3 * i], &g[3 * j]));
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

// `fit` (optional): only these nodes fit their multipliers, and only bonds between two of them
// change; `update` (optional): the rows to sweep (those of `fit`). Null: every node and row.
void moment_method(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                   const std::vector<double>& block_modulus, bool state_based,
                   const std::vector<std::uint32_t>* fit = nullptr,
                   const std::vector<std::uint32_t>* update = nullptr,
                   const HeldRowsShare* held = nullptr) {
  const int D = ns.dim;
  const MomentBasis basis(D, state_based);
  const int T = basis.size();
  const std::size_t n = ns.size();
  const bool windowed = fit != nullptr;
  const std::size_t n_fit = fit ? fit->size() : n, n_update = update ? update->size() : n;
  // Multipliers by slot: node i's is slot i, or its place in `fit`.
  std::vector<std::int64_t> slot;
  if (fit) {
    slot.assign(n, -1);
    for (std::size_t q = 0; q < n_fit; ++q) slot[(*fit)[q]] = static_cast<std::int64_t>(q);
  }
  std::vector<double> p(static_cast<std::size_t>(T) * n_fit);
  std::vector<double> unit(static_cast<std::size_t>(T));
  for (int t = 0; t < T; ++t) unit[t] = basis.identity(t);
  const auto multiplier = [&](std::size_t i) -> const double* {
    if (!fit) return &p[T * i];
    return slot[i] < 0 ? unit.data() : &p[T * static_cast<std::size_t>(slot[i])];
  };
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
    for (std::size_t q = 0; q < n_fit; ++q) {
      const std::size_t i = fit ? (*fit)[q] : q;
      for (int t = 0; t < T; ++t) p[T * q + t] = basis.identity(t);
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
        // Bonds to nodes outside the fit keep their factors: their moments are the target's
        // given part, so that the bonds that do change reach it in one step.
        double held[15] = {};
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
          double nv[3], gb[15], mb[15];
          unit_direction(ns, bf, i, k, nv);
          b.terms(nv, gb, mb);
          const double wt = energy_weight(ns, bf, shape, i, k, state_based);
          m_i += wt;
          if (windowed && slot[bf.neighbor[k]] < 0) {
            for (int a = 0; a < Tb; ++a) held[a] += wt * mb[a];
            continue;
          }
          for (int a = 0; a < Tb; ++a)
            for (int c = 0; c < Tb; ++c) A(a, c) += wt * mb[a] * gb[c];
        }
        if (state_based) axial = 3.0 * m_i / (D * (D + 2));
        for (int t = 0; t < Tb; ++t) r(t) = b.target(t, axial) - held[t];
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
      for (int t = 0; t < T; ++t) p[T * q + t] = sol[t];
    }
    if (held) held->owners(p, T);
    double worst = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : worst)
    for (std::size_t q = 0; q < n_update; ++q) {
      const std::size_t i = update ? (*update)[q] : q;
      if (!(ns.flags[i] & kActive)) continue;
      const double* pi = multiplier(i);
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        const std::uint32_t j = bf.neighbor[k];
        const double* pj = multiplier(j);
        // A bond to a node outside the fit keeps its factor: that node's moments stay as they are.
        if (fit && (pi == unit.data() || pj == unit.data())) continue;
        double nv[3], gb[15], mb[15], gi = 0, gj = 0;
        unit_direction(ns, bf, i, k, nv);
        basis.terms(nv, gb, mb);
        for (int t = 0; t < T; ++t) gi += pi[t] * gb[t], gj += pj[t] * gb[t];
        gi = std::clamp(gi, kMinStep, kMaxStep);
        gj = std::clamp(gj, kMinStep, kMaxStep);
        const double g = std::pow(gi * gj, 0.5 * kRelaxation);
        worst = std::max(worst, std::abs(g - 1));
        bf.beta[k] = static_cast<float>(static_cast<double>(bf.beta[k]) * g);
      }
    }
    if (held) worst = held->max(worst);
    if (worst < kTolerance) break;
  }
}

// Active nodes outside `in` next to it: a neighbour in one of its rows, or a row with a neighbour
// in it (horizons differ across levels, so the two need not coincide).
std::vector<std::uint32_t> ring_around(const NodeSet& ns, const BondFamilies& bf,
                                       const std::vector<char>& in,
                                       const std::vector<std::uint32_t>& in_list) {
  const std::size_t n = ns.size();
  std::vector<char> out(n, 0);
  for (std::uint32_t i : in_list)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::uint32_t j = bf.neighbor[k];
      if (!in[j] && (ns.flags[j] & kActive)) out[j] = 1;
    }
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::size_t i = 0; i < n; ++i) {
    if (in[i] || out[i] || !(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
      if (in[bf.neighbor[k]]) {
        out[i] = 1;
        break;
      }
  }
  std::vector<std::uint32_t> list;
  for (std::size_t i = 0; i < n; ++i)
    if (out[i]) list.push_back(static_cast<std::uint32_t>(i));
  return list;
}

// The searched entry of neighbour j in a row of quadrature_factors(), or null.
const QuadratureEntry* find_entry(const std::vector<QuadratureEntry>& row, std::uint32_t j) {
  const auto it = std::lower_bound(row.begin(), row.end(), j,
                                   [](const QuadratureEntry& e, std::uint32_t v) { return e.j < v; });
  return it != row.end() && it->j == j ? &*it : nullptr;
}

}  // namespace

std::vector<std::uint32_t> correct_surface_window(
    const NodeSet& ns, BondFamilies& bf, const QuadratureSpec& quad, InfluenceShape shape,
    double M, SurfaceCorrection method, bool state_based, const std::vector<double>& block_modulus,
    const std::vector<char>& fresh) {
  if (method == SurfaceCorrection::None) return {};
  const std::size_t n = ns.size();
  std::vector<char> in(n, 0);
  std::vector<std::uint32_t> window;
  for (std::size_t i = 0; i < n; ++i)
    if (i < fresh.size() && fresh[i] && (ns.flags[i] & kActive)) {
      in[i] = 1;
      window.push_back(static_cast<std::uint32_t>(i));
    }
  if (window.empty()) return {};
  const std::vector<std::uint32_t> ring = ring_around(ns, bf, in, window);
  const auto searched = quadrature_factors(ns, quad, ring);
  if (method == SurfaceCorrection::Energy || ns.dim == 1) {
    std::vector<std::int64_t> slot(n, -1);
    std::vector<double> g(3 * (window.size() + ring.size()), 1.0);
    for (std::size_t q = 0; q < window.size(); ++q) slot[window[q]] = static_cast<std::int64_t>(q);
    for (std::size_t q = 0; q < ring.size(); ++q)
      slot[ring[q]] = static_cast<std::int64_t>(window.size() + q);
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t q = 0; q < window.size(); ++q) {
      const std::uint32_t i = window[q];
      energy_factors(ns, shape, M, block_modulus, i,
                     [&](auto&& visit) { row_bonds(bf, i, visit); }, &g[3 * q]);
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t q = 0; q < ring.size(); ++q) {
      const std::uint32_t i = ring[q];
      energy_factors(ns, shape, M, block_modulus, i,
                     [&](auto&& visit) {
                       for (const QuadratureEntry& e : searched[q])
                         visit(e.j, 1.0 / e.inv_length, static_cast<double>(e.beta));
                     },
                     &g[3 * (window.size() + q)]);
    }
    // Every neighbour of a window row is in the window or the ring.
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t q = 0; q < window.size(); ++q) {
      const std::uint32_t i = window[q];
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        const std::uint32_t j = bf.neighbor[k];
        if (slot[j] < 0) continue;
        bf.beta[k] = static_cast<float>(
            static_cast<double>(bf.beta[k]) /
            energy_bond_divisor(ns, i, j, bf.length(k), &g[3 * q], &g[3 * static_cast<std::size_t>(slot[j])]));
      }
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t q = 0; q < ring.size(); ++q) {
      const std::uint32_t i = ring[q];
      const double* gi = &g[3 * (window.size() + q)];
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        const std::uint32_t j = bf.neighbor[k];
        if (!in[j]) continue;
        const QuadratureEntry* e = find_entry(searched[q], j);
        if (!e) continue;
        const double b = static_cast<double>(e->beta) /
                         energy_bond_divisor(ns, i, j, bf.length(k), gi,
                                             &g[3 * static_cast<std::size_t>(slot[j])]);
        bf.beta[k] = static_cast<float>(BondFamilies::intact(bf.beta[k]) ? b : -b);
      }
    }
    return ring;
  }
  // Moments. Every bond between two fitted nodes (the window and the ring) starts from its
  // quadrature factor, as a correction from scratch does; only the bonds to nodes beyond keep
  // theirs. The fixed point is not unique: refits started from the old corrected factors would
  // move away from the whole model's one event after event (stiffer rows, a shorter stable
  // step), though every node meets the bulk moments either way.
  std::vector<char> in_ring(n, 0);
  for (std::uint32_t j : ring) in_ring[j] = 1;
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t q = 0; q < ring.size(); ++q) {
    const std::uint32_t j = ring[q];
    for (std::uint64_t k = bf.begin(j); k < bf.end(j); ++k) {
      const std::uint32_t i = bf.neighbor[k];
      if (!in[i] && !in_ring[i]) continue;
      const QuadratureEntry* e = find_entry(searched[q], i);
      if (!e) continue;
      bf.beta[k] = BondFamilies::intact(bf.beta[k]) ? e->beta : -e->beta;
    }
  }
  std::vector<std::uint32_t> fit = window;
  fit.insert(fit.end(), ring.begin(), ring.end());
  moment_method(ns, bf, shape, M, block_modulus, state_based, &fit, &fit);
  return ring;
}

void apply_surface_correction(const NodeSet& ns, BondFamilies& bf, InfluenceShape shape, double M,
                              SurfaceCorrection method, bool state_based,
                              const std::vector<double>& block_modulus,
                              const HeldRowsShare* held) {
  if (method == SurfaceCorrection::None) return;
  if (method == SurfaceCorrection::Moments && ns.dim > 1)
    moment_method(ns, bf, shape, M, block_modulus, state_based, nullptr, nullptr, held);
  else
    energy_method(ns, bf, shape, M, block_modulus, held);
}

}  // namespace periadapt
