#include "material/lps.hpp"

#include <algorithm>
#include <cmath>

#include "material/row_output.hpp"

namespace periadapt {

LpsConstants lps_constants(int dim, PlaneCondition plane, double E, double nu) {
  LpsConstants c;
  c.mu = E / (2 * (1 + nu));
  if (dim == 3) {
    c.kappa = E / (3 * (1 - 2 * nu));
    c.D = 3;
    c.alpha = 15;
  } else {
    c.kappa = plane == PlaneCondition::Stress ? E / (2 * (1 - nu)) : E / (2 * (1 + nu) * (1 - 2 * nu));
    c.D = 2;
    c.alpha = 8;
  }
  return c;
}

double lps_critical_stretch(int dim, const LpsConstants& c, double delta, double G0) {
  if (dim == 3)
    return std::sqrt(G0 / ((3 * c.mu + std::pow(0.75, 4) * (c.kappa - 5 * c.mu / 3)) * delta));
  return std::sqrt(G0 / ((6 * c.mu / M_PI + 16 / (9 * M_PI * M_PI) * (c.kappa - 2 * c.mu)) * delta));
}

namespace {

template <InfluenceShape S>
inline double omega(double t) {
  return influence_at<S>(t);
}

// Pass 1: weighted volume (all bonds) and dilatation (intact bonds) of every active node, and
// the packed per-node factors of the force pass. Branch-free inner loop (vectorizes).
// `rows`: these nodes' only (a pass's rows and their neighbours); the others keep their values
// (nodes new since the last pass start at 0), so that the dilatation field stays whole after a
// pass over some rows.
template <int D, InfluenceShape S, bool Mutual>
void dilatation(const NodeSet& ns, const BondFamilies& bf, const LpsConstants& c, LpsScratch& sc,
                const std::vector<std::uint32_t>* rows) {
  const std::size_t n = ns.size();
  const std::size_t n_rows = rows ? rows->size() : n;
  const std::uint32_t* row = rows ? rows->data() : nullptr;
  if (rows) {
    sc.m.resize(n, 0.0);
    sc.theta.resize(n, 0.0);
    sc.packed.resize(4 * n, 0.0);
    sc.reach.resize(n, INFINITY);
  } else {
    sc.m.assign(n, 0.0);
    sc.theta.assign(n, 0.0);
    sc.packed.assign(4 * n, 0.0);
    sc.reach.assign(n, INFINITY);
  }
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* inv_len = bf.inv_length.data();
  const float* beta = bf.beta.data();
  // Each family's longest bond first: the next loop keeps only bonds whose far end's family
  // holds the near end too (every bond without Mutual: the dual-horizon form's states).
  // With `rows`, only the families the passes read: the rows' and their far ends'.
  std::vector<char> needed;
  if (Mutual && row) {
    needed.assign(n, 0);
    for (std::size_t r = 0; r < n_rows; ++r) {
      needed[row[r]] = 1;
      for (std::uint64_t k = bf.begin(row[r]); k < bf.end(row[r]); ++k) needed[nbr[k]] = 1;
    }
  }
#pragma omp parallel for schedule(dynamic, 512) if (Mutual)
  for (std::size_t i = 0; i < (Mutual ? n : 0); ++i) {
    if (!(ns.flags[i] & kActive) || (row && !needed[i])) continue;
    double shortest_inv = INFINITY;
#pragma omp simd reduction(min : shortest_inv)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k)
      shortest_inv = std::min(shortest_inv, std::abs(inv_len[k]));
    sc.reach[i] = 1.0 / shortest_inv;
  }
  const double* reach = sc.reach.data();
  const double* yp = ns.cur.data();
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t r = 0; r < n_rows; ++r) {
    const std::size_t i = row ? row[r] : r;
    if (!(ns.flags[i] & kActive)) continue;
    const double inv_delta = 1.0 / ns.horizon[i];
    const double yi0 = yp[4 * i], yi1 = D > 1 ? yp[4 * i + 1] : 0.0, yi2 = D > 2 ? yp[4 * i + 2] : 0.0;
    double m = 0, th = 0;
#pragma omp simd reduction(+ : m, th)
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
      const double d0 = yp[j] - yi0, d1 = D > 1 ? yp[j + 1] - yi1 : 0.0, d2 = D > 2 ? yp[j + 2] - yi2 : 0.0;
      const double x = 1.0 / std::abs(inv_len[k]);
      const double bb = beta[k];
      const double ab = std::abs(bb), bp = 0.5 * (bb + ab);
      double wv = yp[j + 3] * static_cast<double>(x <= reach[nbr[k]]);
      if constexpr (S != InfluenceShape::Constant) wv *= omega<S>(x * inv_delta);
      m += wv * ab * x * x;
      th += wv * bp * x * (std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) - x);
    }
    const double theta = m > 0 ? c.D * th / m : 0.0;
    sc.m[i] = m;
    sc.theta[i] = theta;
    double* p = &sc.packed[4 * i];
    const LpsConstants& ci = node_constants(c, sc, ns, i);
    p[0] = m > 0 ? c.D * ci.kappa * theta / m : 0.0;
    p[1] = m > 0 ? c.alpha * ci.mu / m : 0.0;
    p[2] = theta / c.D;
    p[3] = inv_delta;
  }
}

// B: several materials: stretches compared as s * isf by the far end's block. R: the far end's
// state weighs the pair with its own row's quadrature factor (bf.reverse_beta, for the rows at
// level interfaces); without R both ends' factors are the same.
template <int D, InfluenceShape S, bool E, bool B, bool R>
std::size_t forces(NodeSet& ns, BondFamilies& bf, const LpsConstants& c, bool allow_breaking,
                   LpsScratch& sc, std::vector<std::uint64_t>* log, double* W, const PdroSpec* pdro,
                   const std::vector<std::uint32_t>* rows,
                   const std::vector<std::uint32_t>* dilatation_rows, double* smax_out) {
  dilatation<D, S, true>(ns, bf, c, sc, dilatation_rows);
  const std::size_t n = rows ? rows->size() : ns.size();
  const std::uint32_t* row = rows ? rows->data() : nullptr;
  const double* yp = ns.cur.data();
  const double* pk = sc.packed.data();
  const double* reach = sc.reach.data();
  const std::uint32_t* nbr = bf.neighbor.data();
  const double* inv_len = bf.inv_length.data();
  float* beta = bf.beta.data();
  const std::uint8_t* blk = B ? ns.block.data() : nullptr;
  const std::size_t nblocks = sc.block_constants.size();
  std::size_t broken_total = 0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : broken_total)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = row ? row[r] : r;
    if (!(ns.flags[i] & kActive)) continue;
    const double Ai = pk[4 * i], Bi = pk[4 * i + 1], Ci = pk[4 * i + 2], idi = pk[4 * i + 3];
    const double yi0 = yp[4 * i], yi1 = D > 1 ? yp[4 * i + 1] : 0.0, yi2 = D > 2 ? yp[4 * i + 2] : 0.0;
    const double s0 = (allow_breaking && !(ns.flags[i] & kNoFail)) ? ns.critical_stretch[i] : INFINITY;
    const std::uint64_t kb = bf.begin(i), ke = bf.end(i);
    const double* isf = B ? sc.block_inv_stretch.data() + blk[i] * nblocks : nullptr;
    // The far ends' factors, by place in the row: a row at a level interface has them in
    // reverse_beta; any other row's are its own (bji is then bp, an intact bond's magnitude).
    const float* far = (R && bf.reverse_at[i] != BondFamilies::kNoReverse)
                           ? bf.reverse_beta.data() + bf.reverse_at[i]
                           : beta + kb;
    double a0 = 0, a1 = 0, a2 = 0, wdev = 0, smax = -INFINITY;
    // Fast pass: t_ij + t_ji of intact bonds and the largest stretch of the intact breakable ones
    // (the only ones that can break, and the stretch trigger's measure); nothing written per bond.
#pragma omp simd reduction(+ : a0, a1, a2, wdev) reduction(max : smax)
    for (std::uint64_t k = kb; k < ke; ++k) {
      const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
      const double d0 = yp[j] - yi0, d1 = D > 1 ? yp[j + 1] - yi1 : 0.0, d2 = D > 2 ? yp[j + 2] - yi2 : 0.0;
      const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      const double ail = std::abs(inv_len[k]);
      const double x = 1.0 / ail;
      const double bb = beta[k];
      const double bp = 0.5 * (bb + std::abs(bb));
      const double e = r - x;
      const double mutual = static_cast<double>(x <= reach[nbr[k]]);
      double wi = mutual, wj = mutual;
      if constexpr (S != InfluenceShape::Constant) {
        wi *= omega<S>(x * idi);
        wj *= omega<S>(x * pk[j + 3]);
      }
      const double edi = e - Ci * x;
      const double ti = wi * (Ai * x + Bi * edi), tj = wj * (pk[j] * x + pk[j + 1] * (e - pk[j + 2] * x));
      double fr;
      if constexpr (R)
        fr = (ti * bp + tj * std::abs(static_cast<double>(far[k - kb])) * static_cast<double>(bp > 0.0)) *
             yp[j + 3] / r;
      else
        fr = (ti + tj) * bp * yp[j + 3] / r;
      a0 += fr * d0;
      a1 += fr * d1;
      a2 += fr * d2;
      if constexpr (E) wdev += wi * edi * edi * bp * yp[j + 3];
      double s = e * ail;
      if constexpr (B) s *= isf[blk[nbr[k]]];
      const bool breakable = bp > 0.0 && inv_len[k] > 0.0;
      smax = smax > (breakable ? s : -INFINITY) ? smax : (breakable ? s : -INFINITY);
    }
    if (smax > s0) {
      // Rare: a bond breaks now; break it and redo the node without it.
      a0 = a1 = a2 = wdev = 0;
      smax = -INFINITY;
      double bw = 0;
      std::size_t nb = 0;
      for (std::uint64_t k = kb; k < ke; ++k) {
        const float b = beta[k];
        if (!(b > 0.0f)) continue;
        const std::size_t j = 4 * static_cast<std::size_t>(nbr[k]);
        const double d0 = yp[j] - yi0, d1 = D > 1 ? yp[j + 1] - yi1 : 0.0, d2 = D > 2 ? yp[j + 2] - yi2 : 0.0;
        const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        const double x = 1.0 / std::abs(inv_len[k]);
        const double e = r - x;
        const double V = yp[j + 3] * static_cast<double>(b);
        if (inv_len[k] > 0.0 && (B ? e * isf[blk[nbr[k]]] : e) > s0 * x && (!pdro || pdro_bond_breaks(ns, bf, i, k, s0, *pdro))) {
          beta[k] = -b;
          bw += V;
          ++nb;
          if (log) {
#pragma omp critical(lps_broken_log)
            log->push_back(k);
          }
          continue;
        }
        if (inv_len[k] > 0.0) {
          double s = e * std::abs(inv_len[k]);
          if constexpr (B) s *= isf[blk[nbr[k]]];
          smax = std::max(smax, s);
        }
        const double mutual = static_cast<double>(x <= reach[nbr[k]]);
        double wi = mutual, wj = mutual;
        if constexpr (S != InfluenceShape::Constant) {
          wi *= omega<S>(x * idi);
          wj *= omega<S>(x * pk[j + 3]);
        }
        const double edi = e - Ci * x;
        const double ti = wi * (Ai * x + Bi * edi), tj = wj * (pk[j] * x + pk[j + 1] * (e - pk[j + 2] * x));
        double fr;
        if constexpr (R)
          fr = (ti * b + tj * std::abs(static_cast<double>(far[k - kb]))) * yp[j + 3] / r;
        else
          fr = (ti + tj) * V / r;
        a0 += fr * d0;
        a1 += fr * d1;
        a2 += fr * d2;
        if constexpr (E) wdev += wi * edi * edi * V;
      }
      ns.broken_weight[i] += bw;
      broken_total += nb;
    }
    if (smax_out) smax_out[i] = smax;
    ns.f[0][i] = a0;
    if constexpr (D > 1) ns.f[1][i] = a1;
    if constexpr (D > 2) ns.f[2][i] = a2;
    if constexpr (E)
      W[i] = 0.5 * node_constants(c, sc, ns, i).kappa * sc.theta[i] * sc.theta[i] + 0.5 * Bi * wdev;
  }
  return broken_total;
}

template <int D, bool E, bool B>
std::size_t forces_shape(InfluenceShape s, NodeSet& ns, BondFamilies& bf, const LpsConstants& c,
                         bool brk, LpsScratch& sc, std::vector<std::uint64_t>* log, double* W,
                         const PdroSpec* pdro, const std::vector<std::uint32_t>* rows,
                         const std::vector<std::uint32_t>* dr, double* sm) {
  auto go = [&]<bool R>() {
    switch (s) {
      case InfluenceShape::Constant:
        return forces<D, InfluenceShape::Constant, E, B, R>(ns, bf, c, brk, sc, log, W, pdro, rows,
                                                            dr, sm);
      case InfluenceShape::Triangular:
        return forces<D, InfluenceShape::Triangular, E, B, R>(ns, bf, c, brk, sc, log, W, pdro,
                                                              rows, dr, sm);
      default:
        return forces<D, InfluenceShape::InvertedTriangular, E, B, R>(ns, bf, c, brk, sc, log, W,
                                                                      pdro, rows, dr, sm);
    }
  };
  return bf.reverse_at.empty() ? go.template operator()<false>() : go.template operator()<true>();
}

template <bool E>
std::size_t forces_dim(InfluenceShape s, NodeSet& ns, BondFamilies& bf, const LpsConstants& c,
                       bool brk, LpsScratch& sc, std::vector<std::uint64_t>* log, double* W,
                       const PdroSpec* pdro, const std::vector<std::uint32_t>* rows,
                       const std::vector<std::uint32_t>* dr, double* sm) {
  if (!sc.block_constants.empty())
    return ns.dim == 3 ? forces_shape<3, E, true>(s, ns, bf, c, brk, sc, log, W, pdro, rows, dr, sm)
                       : forces_shape<2, E, true>(s, ns, bf, c, brk, sc, log, W, pdro, rows, dr, sm);
  return ns.dim == 3 ? forces_shape<3, E, false>(s, ns, bf, c, brk, sc, log, W, pdro, rows, dr, sm)
                     : forces_shape<2, E, false>(s, ns, bf, c, brk, sc, log, W, pdro, rows, dr, sm);
}

}  // namespace

std::size_t lps_forces(NodeSet& ns, BondFamilies& bf, InfluenceShape shape, const LpsConstants& c,
                       bool allow_breaking, LpsScratch& sc, std::vector<std::uint64_t>* log,
                       std::vector<double>* Wout, const PdroSpec* pdro,
                       const std::vector<std::uint32_t>* rows,
                       const std::vector<std::uint32_t>* dilatation_rows,
                       std::vector<double>* breakable_stretch) {
  if (pdro && !pdro->enabled) pdro = nullptr;
  double* sm = prepare_row_output(breakable_stretch, ns, rows, -INFINITY);
  if (pdro && allow_breaking && pdro->interpolation == PdroInterpolation::Pim)
    pdro->visible_beta->assign(bf.beta.begin(), bf.beta.end());
  if (Wout) {
    // A pass over some rows changes only theirs; inactive nodes (parents an event switched off)
    // hold none.
    if (rows) {
      Wout->resize(ns.size(), 0.0);
      for (std::size_t i = 0; i < ns.size(); ++i)
        if (!(ns.flags[i] & kActive)) (*Wout)[i] = 0.0;
    } else {
      Wout->assign(ns.size(), 0.0);
    }
    return forces_dim<true>(shape, ns, bf, c, allow_breaking, sc, log, Wout->data(), pdro, rows,
                            dilatation_rows, sm);
  }
  return forces_dim<false>(shape, ns, bf, c, allow_breaking, sc, log, nullptr, pdro, rows,
                           dilatation_rows, sm);
}

namespace {

template <int D, InfluenceShape S, bool Mutual>
void energy(const NodeSet& ns, const BondFamilies& bf, const LpsConstants& c,
            const LpsScratch& sc, std::vector<double>& W, const std::vector<std::uint32_t>* rows) {
  const std::size_t n = rows ? rows->size() : ns.size();
  if (rows) W.resize(ns.size(), 0.0);
  else W.assign(n, 0.0);
  const double* yp = ns.cur.data();
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t i = rows ? (*rows)[q] : q;
    if (!(ns.flags[i] & kActive) || !(sc.m[i] > 0)) {
      W[i] = 0.0;
      continue;
    }
    const double Ci = sc.packed[4 * i + 2], idi = sc.packed[4 * i + 3];
    double wdev = 0;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const float b = bf.beta[k];
      if (!(b > 0.0f)) continue;
      const std::size_t j = 4 * static_cast<std::size_t>(bf.neighbor[k]);
      const double x = bf.length(k);
      double r2 = 0;
      for (int d = 0; d < D; ++d) r2 += std::pow(yp[j + d] - yp[4 * i + d], 2);
      const double ed = std::sqrt(r2) - x - Ci * x;
      if (!Mutual || x <= sc.reach[bf.neighbor[k]])
        wdev += omega<S>(x * idi) * ed * ed * yp[j + 3] * static_cast<double>(b);
    }
    W[i] = 0.5 * node_constants(c, sc, ns, i).kappa * sc.theta[i] * sc.theta[i] +
           0.5 * sc.packed[4 * i + 1] * wdev;
  }
}

template <template <int, InfluenceShape> class Op, class... A>
void by_dim_shape(int dim, InfluenceShape s, A&&... a) {
  auto go = [&]<int D>() {
    switch (s) {
      case InfluenceShape::Constant: Op<D, InfluenceShape::Constant>::run(a...); break;
      case InfluenceShape::Triangular: Op<D, InfluenceShape::Triangular>::run(a...); break;
      default: Op<D, InfluenceShape::InvertedTriangular>::run(a...);
    }
  };
  if (dim == 3) go.template operator()<3>();
  else go.template operator()<2>();
}

template <bool Mutual>
struct DilatationOp {
  template <int D, InfluenceShape S>
  struct Op {
    static void run(const NodeSet& ns, const BondFamilies& bf, const LpsConstants& c,
                    LpsScratch& sc, const std::vector<std::uint32_t>* rows) {
      dilatation<D, S, Mutual>(ns, bf, c, sc, rows);
    }
  };
};
template <bool Mutual>
struct EnergyOp {
  template <int D, InfluenceShape S>
  struct Op {
    static void run(const NodeSet& ns, const BondFamilies& bf, const LpsConstants& c,
                    LpsScratch& sc, std::vector<double>& W, const std::vector<std::uint32_t>* rows) {
      energy<D, S, Mutual>(ns, bf, c, sc, W, rows);
    }
  };
};

}  // namespace

void lps_dilatation(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                    const LpsConstants& c, LpsScratch& sc, bool mutual_only,
                    const std::vector<std::uint32_t>* rows) {
  if (mutual_only)
    by_dim_shape<DilatationOp<true>::Op>(ns.dim, shape, ns, bf, c, sc, rows);
  else
    by_dim_shape<DilatationOp<false>::Op>(ns.dim, shape, ns, bf, c, sc, rows);
}

void lps_energy_density(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                        const LpsConstants& c, LpsScratch& sc, std::vector<double>& W,
                        bool mutual_only, const std::vector<std::uint32_t>* rows) {
  lps_dilatation(ns, bf, shape, c, sc, mutual_only, rows);
  if (mutual_only)
    by_dim_shape<EnergyOp<true>::Op>(ns.dim, shape, ns, bf, c, sc, W, rows);
  else
    by_dim_shape<EnergyOp<false>::Op>(ns.dim, shape, ns, bf, c, sc, W, rows);
}

void lps_stress(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                const LpsConstants& c, LpsScratch& sc, std::vector<double>& sigma,
                bool mutual_only) {
  lps_dilatation(ns, bf, shape, c, sc, mutual_only, nullptr);
  const std::size_t n = ns.size();
  sigma.assign(9 * n, 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive) || !(sc.m[i] > 0)) continue;
    const double* pk = &sc.packed[4 * i];
    double* S = &sigma[9 * i];
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const double b = bf.beta[k];
      const std::uint32_t j = bf.neighbor[k];
      const double x = bf.length(k);
      if (!(b > 0.0) || (mutual_only && x > sc.reach[j])) continue;
      double xi[3], y[3];
      const double r = bond_vectors(ns, i, j, xi, y);
      // t_ij of node i's own state: its energy density's derivative (no 1/2, unlike PMB's pair
      // force, which both ends' densities share).
      const double w = influence(shape, std::min(1.0, x * pk[3]));
      const double t = w * (pk[0] * x + pk[1] * (r - x - pk[2] * x));
      const double f = t * b * ns.volume[j] / r;
      for (int a = 0; a < ns.dim; ++a)
        for (int e = 0; e < ns.dim; ++e) S[3 * a + e] += f * y[a] * xi[e];
    }
  }
}

}  // namespace periadapt
