#include "material/pmb_dual.hpp"

#include <algorithm>
#include <cmath>

#include "material/kernel_dispatch.hpp"

namespace periadapt {

namespace {

// Raw views of the arrays the pass reads, hoisted so the compiler need not reload them after
// every store (the force arrays could otherwise alias them).
struct DualView {
  const double* y;  // packed current positions and volumes, 4 per node
  const double* horizon;
  const double* c;  // micromodulus
  const std::uint32_t* nb;
  const double* inv_len;
  const float* beta;
};

template <int D, InfluenceShape S>
struct DualForces {
  // Two passes: each node evaluates its own memberships once (force on itself, and the factor
  // q = c/2 g s beta / r kept per membership), then gathers the reactions of the memberships that
  // point at it: q V_owner (y_owner - y_i), instead of evaluating each membership a second time
  // from the bond's length, beta and the owner's horizon and micromodulus (2x faster here).
  static std::size_t run(NodeSet& ns, BondFamilies& bf, bool allow_breaking,
                         std::vector<std::uint64_t>* log, std::vector<double>* Wout,
                         const DualRows& split) {
    const std::size_t n = ns.size();
    const std::size_t n_first = split.count(n, false), n_rows = split.count(n, true);
    const DualView v{ns.cur.data(), ns.horizon.data(), ns.micromodulus.data(), bf.neighbor.data(),
                     bf.inv_length.data(), bf.beta.data()};
    const std::uint64_t* begins = bf.offsets.data();
    const std::uint64_t* ends = bf.row_ends();
    const std::uint64_t* t_off = bf.t_offsets.data();
    const std::uint32_t* t_owner = bf.t_owner.data();
    const std::uint64_t* t_bond = bf.t_bond.data();
    const std::uint8_t* flags = ns.flags.data();
    const double* s0s = ns.critical_stretch.data();
    double* f[3] = {ns.f[0].data(), ns.f[1].data(), ns.f[2].data()};
    if (bf.dual_force.size() != bf.neighbor.size()) bf.dual_force.assign(bf.neighbor.size(), 0.0);
    double* fac = bf.dual_force.data();
    double* W = nullptr;
    if (Wout) {
      Wout->assign(n, 0.0);
      W = Wout->data();
    }
    // (bond, owner): after a refinement event rows are no longer stored in node order, so the
    // owner is recorded, not inferred from the bond's index.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> newly;
#pragma omp parallel
    {
      std::vector<std::pair<std::uint64_t, std::uint32_t>> mine;
#pragma omp for schedule(dynamic, 512)
      for (std::size_t r = 0; r < n_first; ++r) {
        const std::size_t i = split.at(r, false);
        if (!(flags[i] & kActive)) {
          for (std::uint64_t k = begins[i]; k < ends[i]; ++k) fac[k] = 0.0;
          continue;
        }
        const double s0 = (allow_breaking && !(flags[i] & kNoFail)) ? s0s[i] : INFINITY;
        const double half_c = 0.5 * v.c[i], h = v.horizon[i];
        double a[3] = {0, 0, 0}, w = 0;
        for (std::uint64_t k = begins[i]; k < ends[i]; ++k) {
          fac[k] = 0.0;
          if (!BondFamilies::intact(v.beta[k])) continue;
          const std::size_t j = v.nb[k];
          double d[3] = {0, 0, 0}, r2 = 0;
          for (int e = 0; e < D; ++e) {
            d[e] = v.y[4 * j + e] - v.y[4 * i + e];
            r2 += d[e] * d[e];
          }
          const double ail = std::abs(v.inv_len[k]);
          const double r = std::sqrt(r2);
          const double s = r * ail - 1.0;
          // Broken in this pass: no force either way (breaking applied after the pass).
          if (v.inv_len[k] > 0.0 && s > s0) {
            if (split.breaks_here(i)) mine.emplace_back(k, static_cast<std::uint32_t>(i));
            continue;
          }
          const double g = influence_at<S>(1.0 / (ail * h));
          const double q = half_c * g * s * static_cast<double>(v.beta[k]) / r;
          const double fr = q * v.y[4 * j + 3];
          fac[k] = q;
          for (int e = 0; e < D; ++e) a[e] += fr * d[e];
          if (W) w += g * s * s / ail * static_cast<double>(v.beta[k]) * v.y[4 * j + 3];
        }
        for (int e = 0; e < D; ++e) f[e][i] = a[e];
        if (W) W[i] = 0.25 * v.c[i] * w;
      }
      // Reactions: every membership (o, k) pointing at i pulls i towards o with o's factor.
#pragma omp for schedule(dynamic, 512)
      for (std::size_t r = 0; r < n_rows; ++r) {
        const std::size_t i = split.at(r, true);
        if (!(flags[i] & kActive)) continue;
        double a[3];
        for (int e = 0; e < D; ++e) a[e] = f[e][i];
        for (std::uint64_t q = t_off[i]; q < t_off[i + 1]; ++q) {
          const double qk = fac[t_bond[q]];
          if (qk == 0.0) continue;
          const std::size_t o = t_owner[q];
          const double fr = qk * v.y[4 * o + 3];
          for (int e = 0; e < D; ++e) a[e] += fr * (v.y[4 * o + e] - v.y[4 * i + e]);
        }
        for (int e = 0; e < D; ++e) f[e][i] = a[e];
      }
#pragma omp critical(pmb_dual_broken)
      newly.insert(newly.end(), mine.begin(), mine.end());
    }
    // Bonds broken in this pass, in a fixed order so the result does not depend on the threads.
    std::sort(newly.begin(), newly.end());
    for (const auto& [k, i] : newly) {
      const std::size_t j = bf.neighbor[k];
      ns.broken_weight[i] += static_cast<double>(bf.beta[k]) * ns.volume[j];
      bf.beta[k] = -bf.beta[k];
      if (log) log->push_back(k);
    }
    return newly.size();
  }
};

}  // namespace

std::size_t pmb_dual_forces(NodeSet& ns, BondFamilies& bf, InfluenceShape shape,
                            bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* Wout, const DualRows& split) {
  return dispatch<DualForces>(ns.dim, shape, ns, bf, allow_breaking, log, Wout, split);
}

}  // namespace periadapt
