#include "material/pmb_dual.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

namespace {

inline double shape_g(InfluenceShape s, double t) { return influence(s, t < 1.0 ? t : 1.0); }

// Force density on `at` from membership k (owner o, target j): c_o/2 g s beta V_other e.
inline void membership_force(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                             std::uint64_t k, std::size_t owner, std::size_t at, std::size_t other,
                             double out[3]) {
  const double* yp = ns.cur.data();
  double d[3] = {0, 0, 0}, r2 = 0;
  for (int e = 0; e < ns.dim; ++e) {
    d[e] = yp[4 * other + e] - yp[4 * at + e];
    r2 += d[e] * d[e];
  }
  const double r = std::sqrt(r2), ail = std::abs(bf.inv_length[k]);
  const double s = r * ail - 1.0;
  const double g = shape_g(shape, 1.0 / (ail * ns.horizon[owner]));
  const double fr = 0.5 * ns.micromodulus[owner] * g * s * static_cast<double>(bf.beta[k]) *
                    yp[4 * other + 3] / r;
  for (int e = 0; e < ns.dim; ++e) out[e] = fr * d[e];
}

}  // namespace

std::size_t pmb_dual_forces(NodeSet& ns, BondFamilies& bf, InfluenceShape shape,
                            bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* Wout) {
  const std::size_t n = ns.size();
  const double* yp = ns.cur.data();
  if (Wout) Wout->assign(n, 0.0);
  std::vector<std::uint64_t> newly;
#pragma omp parallel
  {
    std::vector<std::uint64_t> mine;
#pragma omp for schedule(dynamic, 512)
    for (std::size_t i = 0; i < n; ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const double s0 =
          (allow_breaking && !(ns.flags[i] & kNoFail)) ? ns.critical_stretch[i] : INFINITY;
      double a[3] = {0, 0, 0}, w = 0;
      // Own memberships (j in H(i)): force on i; breaking decided here, applied after the pass.
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
        if (!BondFamilies::intact(bf.beta[k])) continue;
        const std::size_t j = bf.neighbor[k];
        double r2 = 0;
        for (int e = 0; e < ns.dim; ++e) {
          const double t = yp[4 * j + e] - yp[4 * i + e];
          r2 += t * t;
        }
        const double ail = std::abs(bf.inv_length[k]);
        const double s = std::sqrt(r2) * ail - 1.0;
        if (bf.inv_length[k] > 0.0 && s > s0) {
          mine.push_back(k);
          continue;
        }
        double f[3];
        membership_force(ns, bf, shape, k, i, i, j, f);
        for (int e = 0; e < ns.dim; ++e) a[e] += f[e];
        if (Wout) {
          const double g = shape_g(shape, 1.0 / (ail * ns.horizon[i]));
          w += g * s * s / ail * static_cast<double>(bf.beta[k]) * yp[4 * j + 3];
        }
      }
      // Memberships of other families pointing at i (dual horizon): the reactions.
      for (std::uint64_t q = bf.t_offsets[i]; q < bf.t_offsets[i + 1]; ++q) {
        const std::uint64_t k = bf.t_bond[q];
        if (!BondFamilies::intact(bf.beta[k])) continue;
        const std::size_t o = bf.t_owner[q];
        double f[3];
        membership_force(ns, bf, shape, k, o, i, o, f);
        for (int e = 0; e < ns.dim; ++e) a[e] += f[e];
      }
      for (int e = 0; e < ns.dim; ++e) ns.f[e][i] = a[e];
      if (Wout) (*Wout)[i] = 0.25 * ns.micromodulus[i] * w;
    }
#pragma omp critical(pmb_dual_broken)
    newly.insert(newly.end(), mine.begin(), mine.end());
  }
  // Bonds broken in this pass: their targets still got the reaction; take it back, in a fixed
  // order so the result does not depend on the threads.
  std::sort(newly.begin(), newly.end());
  std::vector<std::uint32_t> owner_of;
  if (!newly.empty()) {
    owner_of.resize(newly.size());
    std::size_t o = 0;
    for (std::size_t q = 0; q < newly.size(); ++q) {
      while (bf.end(o) <= newly[q]) ++o;
      owner_of[q] = static_cast<std::uint32_t>(o);
    }
  }
  for (std::size_t q = 0; q < newly.size(); ++q) {
    const std::uint64_t k = newly[q];
    const std::size_t i = owner_of[q], j = bf.neighbor[k];
    double f[3];
    membership_force(ns, bf, shape, k, i, j, i, f);
    for (int e = 0; e < ns.dim; ++e) ns.f[e][j] -= f[e];
    ns.broken_weight[i] += static_cast<double>(bf.beta[k]) * ns.volume[j];
    bf.beta[k] = -bf.beta[k];
    if (log) log->push_back(k);
  }
  return newly.size();
}

}  // namespace periadapt
