#include "material/pmb.hpp"

#include <algorithm>
#include <cmath>

#include "material/kernel_dispatch.hpp"
#include "material/row_output.hpp"

namespace periadapt {

namespace {

template <InfluenceShape S>
inline double g(double t) {
  return influence_at<S>(t);
}

struct RowSums {
  double a0, a1, a2, smax, w, sbreak;
};

// Forces of the intact bonds of one row and their largest stretch; nothing is written per bond.
// Always this one vectorized sum, also right after bonds broke, so that a node's force depends on
// the state only, not on the pass that found a bond broken (a refresh of some rows then
// reproduces a full pass bit for bit). A free function with local accumulators: as a lambda
// with captures GCC 12 no longer vectorizes it (2.6x slower).
// E: in the same sweep also w = sum of g beta V s^2 xi over the intact bonds (4 W_i / c_i), when
// energies are asked for. The extra reduction leaves the force sums as they vectorize without it:
// the forces come out bit for bit the same (tests/test_energy_density.cpp), so they do not
// depend on when energies are asked for.
// T: also the largest stretch of the intact breakable bonds (the stretch trigger's measure).
// B: several materials: each bond's micromodulus factor kf and inverse critical-stretch ratio isf
// by the far end's block blk (material/blocks.hpp); stretches are compared as s * isf.
template <int D, InfluenceShape S, bool E = false, bool T = false, bool B = false>
inline RowSums row_force_sums(const double* yp, const std::uint32_t* nbr, const double* inv_len,
                              const float* beta, std::uint64_t kb, std::uint64_t ke, double yi0,
                              double yi1, double yi2, double ci, double delta, double one_eth,
                              const std::uint8_t* blk = nullptr, const double* kf = nullptr,
                              const double* isf = nullptr) {
  double a0 = 0, a1 = 0, a2 = 0, smax = -INFINITY, w = 0, sbreak = -INFINITY;
#pragma omp simd reduction(+ : a0, a1, a2, w) reduction(max : smax, sbreak)
  for (std::uint64_t k = kb; k < ke; ++k) {
    // 64-bit index arithmetic: a 32-bit 4*j would have to wrap and defeats the gathers.
    const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
    const double d0 = yp[j] - yi0;
    const double d1 = D > 1 ? yp[j + 1] - yi1 : 0.0;
    const double d2 = D > 2 ? yp[j + 2] - yi2 : 0.0;
    const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    const double ail = std::abs(inv_len[k]);
    // 0 when broken. Written branch-free: std::max (returns a reference) or a ternary here
    // makes GCC 12 see control flow and give up vectorizing the whole loop.
    const double bb = beta[k];
    const double bp = 0.5 * (bb + std::abs(bb));
    double gw = bp * yp[j + 3];
    if constexpr (S != InfluenceShape::Constant) gw *= g<S>(1.0 / (ail * delta));
    const double s = r * ail - one_eth;
    double sn = s;
    if constexpr (B) {
      const std::size_t bj = blk[nbr[k]];
      gw *= kf[bj];
      sn *= isf[bj];
    }
    smax = std::max(smax, bp > 0.0 ? sn : -INFINITY);
    if constexpr (T) {
      const double bk = inv_len[k] > 0.0 ? bp : 0.0;
      sbreak = std::max(sbreak, bk > 0.0 ? sn : -INFINITY);
    }
    // One division serves the force and the energy: t = 1/(r ail) = |xi|/r, so s/r = s ail t and
    // |xi| = r t (a second division for |xi| made the energy sweep 29% dearer than the plain one).
    const double t = 1.0 / (r * ail);
    // f = c g s beta V e
    const double fr = ci * gw * s * ail * t;
    a0 += fr * d0;
    a1 += fr * d1;
    a2 += fr * d2;
    if constexpr (E) w += gw * s * s * (r * t);
  }
  return RowSums{a0, a1, a2, smax, w, sbreak};
}

// sum over the intact bonds of one row of g beta V s^2 xi (broken ones weigh 0, branch-free so
// it vectorizes): 4 W_i / c_i. The force pass (when energies are asked for) and the energy
// kernel share it, so both give the same bits.
template <int D, InfluenceShape S, bool B = false>
inline double row_energy_sum(const double* yp, const std::uint32_t* nbr, const double* inv_len,
                             const float* beta, std::uint64_t kb, std::uint64_t ke, double yi0,
                             double yi1, double yi2, double delta, double one_eth,
                             const std::uint8_t* blk = nullptr, const double* kf = nullptr) {
  double w = 0;
#pragma omp simd reduction(+ : w)
  for (std::uint64_t k = kb; k < ke; ++k) {
    const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
    const double d0 = yp[j] - yi0;
    const double d1 = D > 1 ? yp[j + 1] - yi1 : 0.0;
    const double d2 = D > 2 ? yp[j + 2] - yi2 : 0.0;
    const double ail = std::abs(inv_len[k]);
    const double bb = beta[k];
    double gw = 0.5 * (bb + std::abs(bb)) * yp[j + 3];
    if constexpr (S != InfluenceShape::Constant) gw *= g<S>(1.0 / (ail * delta));
    if constexpr (B) gw *= kf[blk[nbr[k]]];
    const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    const double s = r * ail - one_eth;
    // |xi| as the force sweep forms it (r / (r ail)), so both give the same bits.
    w += gw * s * s * (r * (1.0 / (r * ail)));
  }
  return w;
}

// E: also the strain-energy density W_i (thesis Eq. 2.14) of the bonds intact after this call.
// T: also the largest stretch of each row's intact breakable bonds after this call, into smax.
template <int D, InfluenceShape S, bool E, bool T, bool B>
std::size_t forces_kernel(NodeSet& ns, BondFamilies& bf, bool allow_breaking,
                          std::vector<std::uint64_t>* log, double* W, const PdroSpec* pdro,
                          double eth, const std::vector<std::uint32_t>* rows, double* smax_out,
                          const BlockPairs* pairs) {
  const std::size_t n = rows ? rows->size() : ns.size();
  const std::uint32_t* row = rows ? rows->data() : nullptr;
  const double* yp = ns.cur.data();
  const std::uint8_t* flags = ns.flags.data();
  const std::uint64_t* off = bf.offsets.data();
  const std::uint64_t* ends = bf.row_ends();
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* inv_len = bf.inv_length.data();
  float* beta = bf.beta.data();
  double* f0 = ns.f[0].data();
  double* f1 = ns.f[1].data();
  double* f2 = ns.f[2].data();
  const std::uint8_t* blk = B ? ns.block.data() : nullptr;
  std::size_t broken_total = 0;
  // Thermal strain eth = alpha dT: s = r/L - 1 - eth, so s/r = 1/L - (1 + eth)/r.
  const double one_eth = 1.0 + eth;

#pragma omp parallel for schedule(guided, 32) reduction(+ : broken_total)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row ? row[r] : r;
    if (!(flags[i] & kActive)) continue;
    const double yi0 = yp[4 * i];
    const double yi1 = D > 1 ? yp[4 * i + 1] : 0.0;
    const double yi2 = D > 2 ? yp[4 * i + 2] : 0.0;
    const double ci = ns.micromodulus[i];
    // A bond breaks when s > s0; s0 = +inf when this node cannot break bonds.
    const double s0 = (allow_breaking && !(flags[i] & kNoFail)) ? ns.critical_stretch[i] : INFINITY;
    const double delta = ns.horizon[i];
    const std::uint64_t kb = off[i], ke = ends[i];
    const double* kf = B ? pairs->stiffness_row(blk[i]) : nullptr;
    const double* isf = B ? pairs->inv_stretch_row(blk[i]) : nullptr;
    // With energies asked for, one sweep gives both.
    auto sweep = [&]() {
      const RowSums q = row_force_sums<D, S, E, T, B>(yp, nbr, inv_len, beta, kb, ke, yi0, yi1,
                                                      yi2, ci, delta, one_eth, blk, kf, isf);
      if constexpr (E) W[i] = 0.25 * ci * q.w;
      if constexpr (T) smax_out[i] = q.sbreak;
      return q;
    };
    RowSums sums = sweep();
    if (sums.smax > s0) {
      // Rare: some bond of this node breaks now. Break them, then sum the rest again.
      double bw = 0;
      std::size_t nb = 0;
      for (std::uint64_t k = kb; k < ke; ++k) {
        const float b = beta[k];
        if (!(b > 0.0f) || !(inv_len[k] > 0.0)) continue;
        const std::uint32_t j = nbr[k];
        const double d0 = yp[4 * j] - yi0;
        const double d1 = D > 1 ? yp[4 * j + 1] - yi1 : 0.0;
        const double d2 = D > 2 ? yp[4 * j + 2] - yi2 : 0.0;
        double s = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) * inv_len[k] - one_eth;
        if constexpr (B) s *= isf[blk[j]];
        if (s > s0 && (!pdro || pdro_bond_breaks(ns, bf, i, k, s0, *pdro, eth))) {
          beta[k] = -b;
          bw += static_cast<double>(b) * yp[4 * j + 3];
          ++nb;
          if (log) {
#pragma omp critical(pmb_broken_log)
            log->push_back(k);
          }
        }
      }
      ns.broken_weight[i] += bw;
      broken_total += nb;
      if (nb > 0) sums = sweep();
    }
    f0[i] = sums.a0;
    if constexpr (D > 1) f1[i] = sums.a1;
    if constexpr (D > 2) f2[i] = sums.a2;
  }
  return broken_total;
}

template <int D, InfluenceShape S, bool B>
void energy_kernel(const NodeSet& ns, const BondFamilies& bf, double eth, std::vector<double>& W,
                   const std::vector<std::uint32_t>* rows, const BlockPairs* pairs) {
  const std::size_t n = rows ? rows->size() : ns.size();
  const std::uint32_t* row = rows ? rows->data() : nullptr;
  if (rows)
    W.resize(ns.size(), 0.0);
  else
    W.assign(n, 0.0);
  const double* yp = ns.cur.data();
  const std::uint8_t* flags = ns.flags.data();
  const std::uint64_t* off = bf.offsets.data();
  const std::uint64_t* ends = bf.row_ends();
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* inv_len = bf.inv_length.data();
  const float* beta = bf.beta.data();
  const double one_eth = 1.0 + eth;
#pragma omp parallel for schedule(guided, 32)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row ? row[r] : r;
    if (!(flags[i] & kActive)) {
      W[i] = 0.0;
      continue;
    }
    const double yi0 = yp[4 * i];
    const double yi1 = D > 1 ? yp[4 * i + 1] : 0.0;
    const double yi2 = D > 2 ? yp[4 * i + 2] : 0.0;
    W[i] = 0.25 * ns.micromodulus[i] *
           row_energy_sum<D, S, B>(yp, nbr, inv_len, beta, off[i], ends[i], yi0, yi1, yi2,
                                   ns.horizon[i], one_eth, B ? ns.block.data() : nullptr,
                                   B ? pairs->stiffness_row(ns.block[i]) : nullptr);
  }
}

template <InfluenceShape S>
double stiffness_row(const NodeSet& ns, const BondFamilies& bf, std::size_t i,
                     const BlockPairs* pairs) {
  const double inv_delta = 1.0 / ns.horizon[i];
  const double* kf = pairs && pairs->active() ? pairs->stiffness_row(ns.block[i]) : nullptr;
  double k = 0;
  for (std::uint64_t q = bf.begin(i); q < bf.end(i); ++q) {
    const double L = bf.length(q);
    double t = g<S>(L * inv_delta) * std::abs(static_cast<double>(bf.beta[q])) *
               ns.volume[bf.neighbor[q]] / L;
    if (kf) t *= kf[ns.block[bf.neighbor[q]]];
    k += t;
  }
  return ns.micromodulus[i] * k;
}

template <InfluenceShape S>
void stiffness_kernel(const NodeSet& ns, const BondFamilies& bf, std::vector<double>& K,
                      const BlockPairs* pairs) {
  const std::size_t n = ns.size();
  K.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) K[i] = stiffness_row<S>(ns, bf, i, pairs);
}

template <int D, InfluenceShape S, bool B>
std::size_t forces_variant(NodeSet& ns, BondFamilies& bf, bool brk, std::vector<std::uint64_t>* log,
                           double* W, const PdroSpec* pdro, double eth,
                           const std::vector<std::uint32_t>* rows, double* smax,
                           const BlockPairs* pairs) {
  if (smax)
    return W ? forces_kernel<D, S, true, true, B>(ns, bf, brk, log, W, pdro, eth, rows, smax, pairs)
             : forces_kernel<D, S, false, true, B>(ns, bf, brk, log, nullptr, pdro, eth, rows, smax,
                                                   pairs);
  return W ? forces_kernel<D, S, true, false, B>(ns, bf, brk, log, W, pdro, eth, rows, nullptr, pairs)
           : forces_kernel<D, S, false, false, B>(ns, bf, brk, log, nullptr, pdro, eth, rows,
                                                  nullptr, pairs);
}

template <int D, InfluenceShape S>
struct ForcesOp {
  static std::size_t run(NodeSet& ns, BondFamilies& bf, bool brk,
                         std::vector<std::uint64_t>* log, double* W, const PdroSpec* pdro,
                         double eth, const std::vector<std::uint32_t>* rows, double* smax,
                         const BlockPairs* pairs) {
    if (pairs && pairs->active())
      return forces_variant<D, S, true>(ns, bf, brk, log, W, pdro, eth, rows, smax, pairs);
    return forces_variant<D, S, false>(ns, bf, brk, log, W, pdro, eth, rows, smax, nullptr);
  }
};
template <int D, InfluenceShape S>
struct PmbEnergyOp {
  static int run(const NodeSet& ns, const BondFamilies& bf, double eth, std::vector<double>& W,
                 const std::vector<std::uint32_t>* rows, const BlockPairs* pairs) {
    if (pairs && pairs->active())
      energy_kernel<D, S, true>(ns, bf, eth, W, rows, pairs);
    else
      energy_kernel<D, S, false>(ns, bf, eth, W, rows, nullptr);
    return 0;
  }
};
template <int D, InfluenceShape S>
struct StiffnessOp {
  static int run(const NodeSet& ns, const BondFamilies& bf, std::vector<double>& K,
                 const BlockPairs* pairs) {
    stiffness_kernel<S>(ns, bf, K, pairs);
    return 0;
  }
};

}  // namespace

PmbStepStats pmb_forces(NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                        bool allow_breaking, std::vector<std::uint64_t>* broken_log,
                        std::vector<double>* W, const PdroSpec* pdro, double thermal_strain,
                        const std::vector<std::uint32_t>* rows,
                        std::vector<double>* breakable_stretch, const BlockPairs* pairs) {
  PmbStepStats st;
  if (pdro && pdro->enabled && allow_breaking && pdro->interpolation == PdroInterpolation::Pim)
    pdro->visible_beta->assign(bonds.beta.begin(), bonds.beta.end());
  double* w = nullptr;
  if (W && rows) {
    // Only the listed rows change: the others keep their densities; listed inactive nodes
    // (parents switched off by an event) hold none.
    W->resize(nodes.size(), 0.0);
    for (std::uint32_t i : *rows)
      if (!(nodes.flags[i] & kActive)) (*W)[i] = 0.0;
    w = W->data();
  } else if (W) {
    W->assign(nodes.size(), 0.0);
    w = W->data();
  }
  double* sb = prepare_row_output(breakable_stretch, nodes, rows, -INFINITY);
  st.newly_broken =
      dispatch<ForcesOp>(nodes.dim, shape, nodes, bonds, allow_breaking, broken_log, w,
                         pdro && pdro->enabled ? pdro : nullptr, thermal_strain, rows, sb, pairs);
  return st;
}

void pmb_energy_density(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                        std::vector<double>& W, double thermal_strain,
                        const std::vector<std::uint32_t>* rows, const BlockPairs* pairs) {
  dispatch<PmbEnergyOp>(nodes.dim, shape, nodes, bonds, thermal_strain, W, rows, pairs);
}

void pmb_stiffness_sum(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                       std::vector<double>& K, const BlockPairs* pairs) {
  dispatch<StiffnessOp>(nodes.dim, shape, nodes, bonds, K, pairs);
}

double pmb_stiffness_row(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                         std::size_t i, const BlockPairs* pairs) {
  switch (shape) {
    case InfluenceShape::Constant:
      return stiffness_row<InfluenceShape::Constant>(nodes, bonds, i, pairs);
    case InfluenceShape::Triangular:
      return stiffness_row<InfluenceShape::Triangular>(nodes, bonds, i, pairs);
    default: return stiffness_row<InfluenceShape::InvertedTriangular>(nodes, bonds, i, pairs);
  }
}

void pmb_stress(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                std::vector<double>& sigma, double thermal_strain, const BlockPairs* pairs) {
  const bool blocks = pairs && pairs->active();
  const std::size_t n = ns.size();
  sigma.assign(9 * n, 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    double* S = &sigma[9 * i];
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const double b = bf.beta[k];
      if (!(b > 0.0)) continue;
      const std::uint32_t j = bf.neighbor[k];
      const double L = bf.length(k);
      double xi[3], y[3];
      const double r = bond_vectors(ns, i, j, xi, y);
      const double s = r / L - 1.0 - thermal_strain;
      // 1/2 f (x) xi with f = c g s beta V e: the derivative of W_i = c/4 sum g s^2 xi beta V.
      double f = 0.5 * ns.micromodulus[i] * influence(shape, std::min(1.0, L / ns.horizon[i])) *
                 s * b * ns.volume[j] / r;
      if (blocks) f *= pairs->stiffness_row(ns.block[i])[ns.block[j]];
      for (int a = 0; a < ns.dim; ++a)
        for (int c = 0; c < ns.dim; ++c) S[3 * a + c] += f * y[a] * xi[c];
    }
  }
}

}  // namespace periadapt
