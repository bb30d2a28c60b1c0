#pragma once
// The row kernels every history law of material/bond_law.hpp runs on, templated on the law's
// bond response, so a law file holds its physics only. A law type L provides (h: the bond's
// history value, a: onset stretch, b: the row's breaking stretch):
//   static double update(double s, double h, double a, double b);  // history after stretch s
//   static double force(double s, double h, double a, double b);   // F: f = c g F beta V e
//   static double energy(double s, double h, double a, double b);  // phi: W = 1/4 c g phi xi beta V
//   static bool failed(double s, double h, double b);               // the bond breaks
// Unbreakable bonds (an end in a no-fail region) stay on the elastic branch F = s, phi = s^2.
#include <algorithm>
#include <cmath>

#include "material/bond_law.hpp"
#include "material/kernel_dispatch.hpp"
#include "material/row_output.hpp"

namespace periadapt {

template <class L>
struct BondLawKernels {
  // One row: visit(k, j, d0, d1, d2, r, s, gw, len) for each intact bond (d: current bond
  // vector, r its length, s the stretch, gw = g beta V_j, len = |xi|).
  template <int D, InfluenceShape S, class Visit>
  static void for_intact(const NodeSet& ns, const BondFamilies& bf, std::size_t i, Visit&& visit) {
    const double* yp = ns.cur.data();
    const double delta = ns.horizon[i];
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const float b = bf.beta[k];
      if (!(b > 0.0f)) continue;
      const std::size_t j = bf.neighbor[k];
      const double d0 = yp[4 * j] - yp[4 * i];
      const double d1 = D > 1 ? yp[4 * j + 1] - yp[4 * i + 1] : 0.0;
      const double d2 = D > 2 ? yp[4 * j + 2] - yp[4 * i + 2] : 0.0;
      const double ail = std::abs(bf.inv_length[k]);
      const double r = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      double gw = static_cast<double>(b) * yp[4 * j + 3];
      if constexpr (S != InfluenceShape::Constant) gw *= influence_at<S>(1.0 / (ail * delta));
      visit(k, j, d0, d1, d2, r, r * ail - 1.0, gw, 1.0 / ail);
    }
  }

  // A row's force density and energy sums.
  struct RowSum {
    double f0 = 0, f1 = 0, f2 = 0, w = 0;
    void add(double fr, double d0, double d1, double d2, double energy) {
      f0 += fr * d0;
      f1 += fr * d1;
      f2 += fr * d2;
      w += energy;
    }
    template <int D>
    void store_forces(NodeSet& ns, std::size_t i) const {
      ns.f[0][i] = f0;
      if constexpr (D > 1) ns.f[1][i] = f1;
      if constexpr (D > 2) ns.f[2][i] = f2;
    }
  };

  // One intact bond k at stretch s: updates its history and gives its force factor F and
  // energy phi; false when it breaks now. Off the law (`law` false: an end in a no-fail region)
  // the bond stays on the elastic branch.
  static bool respond(BondFamilies& bf, std::uint64_t k, bool law, bool allow_breaking, double s,
                      double a, double b, double& F, double& phi) {
    F = s;
    phi = s * s;
    if (!law) return true;
    const double h = L::update(s, bf.state[k], a, b);
    bf.state[k] = h;
    if (allow_breaking && L::failed(s, h, b)) return false;
    F = L::force(s, h, a, b);
    phi = L::energy(s, h, a, b);
    return true;
  }

  template <int D, InfluenceShape S>
  struct Forces {
    static std::size_t run(NodeSet& ns, BondFamilies& bf, const BondLawCall& c) {
      const std::size_t n = c.rows ? c.rows->size() : ns.size();
      double* W = c.W ? c.W->data() : nullptr;
      double* smax = c.breakable_stretch ? c.breakable_stretch->data() : nullptr;
      const double a = c.onset_stretch;
      std::size_t broken_total = 0;
#pragma omp parallel for schedule(guided, 32) reduction(+ : broken_total)
      for (std::size_t q = 0; q < n; ++q) {
        const std::size_t i = c.rows ? (*c.rows)[q] : q;
        if (!(ns.flags[i] & kActive)) continue;
        const bool node_breaks = !(ns.flags[i] & kNoFail);
        const double b = ns.critical_stretch[i], ci = ns.micromodulus[i];
        RowSum sum;
        double sm = -INFINITY, bw = 0;
        std::size_t nb = 0;
        for_intact<D, S>(ns, bf, i, [&](std::uint64_t k, std::size_t j, double d0, double d1,
                                        double d2, double r, double s, double gw, double len) {
          const bool law = node_breaks && bf.inv_length[k] > 0.0;
          double F, phi;
          if (!respond(bf, k, law, c.allow_breaking, s, a, b, F, phi)) {
            bf.beta[k] = -bf.beta[k];
            bw += -static_cast<double>(bf.beta[k]) * ns.cur[4 * j + 3];
            ++nb;
            if (c.broken_log) {
#pragma omp critical(bond_law_broken_log)
              c.broken_log->push_back(k);
            }
            return;
          }
          if (law) sm = std::max(sm, s);
          sum.add(ci * gw * F / r, d0, d1, d2, gw * phi * len);
        });
        sum.template store_forces<D>(ns, i);
        ns.broken_weight[i] += bw;
        broken_total += nb;
        if (W) W[i] = 0.25 * ci * sum.w;
        if (smax) smax[i] = sm;
      }
      return broken_total;
    }
  };

  // The dual-horizon form: each membership (a bond of i's family) pulls both ends with half of
  // its owner's force, so every pair force is equal and opposite whatever the two horizons.
  // First pass: each owner updates its memberships' histories and keeps q = c/2 g F beta / r
  // per membership (bonds.dual_force); second pass: each node gathers the memberships that
  // point at it (bonds.t_*). Bonds broken in the pass carry no force and break afterwards, in
  // a fixed order.
  template <int D, InfluenceShape S>
  struct DualForces {
    static std::size_t run(NodeSet& ns, BondFamilies& bf, const BondLawCall& c) {
      const std::size_t n = ns.size();
      const DualRows split = c.split ? *c.split : DualRows{};
      const std::size_t n_first = split.count(n, false), n_rows = split.count(n, true);
      if (bf.dual_force.size() != bf.neighbor.size()) bf.dual_force.assign(bf.neighbor.size(), 0.0);
      double* fac = bf.dual_force.data();
      double* W = nullptr;
      if (c.W) {
        c.W->assign(n, 0.0);
        W = c.W->data();
      }
      const double a = c.onset_stretch;
      std::vector<std::pair<std::uint64_t, std::uint32_t>> newly;
#pragma omp parallel
      {
        std::vector<std::pair<std::uint64_t, std::uint32_t>> mine;
#pragma omp for schedule(dynamic, 512)
        for (std::size_t r = 0; r < n_first; ++r) {
          const std::size_t i = split.at(r, false);
          for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) fac[k] = 0.0;
          if (!(ns.flags[i] & kActive)) continue;
          const bool node_breaks = !(ns.flags[i] & kNoFail);
          const double b = ns.critical_stretch[i], half_c = 0.5 * ns.micromodulus[i];
          RowSum sum;
          for_intact<D, S>(ns, bf, i, [&](std::uint64_t k, std::size_t j, double d0, double d1,
                                          double d2, double r, double s, double gw, double len) {
            double F, phi;
            if (!respond(bf, k, node_breaks && bf.inv_length[k] > 0.0, c.allow_breaking, s, a, b,
                         F, phi)) {
              if (split.breaks_here(i)) mine.emplace_back(k, static_cast<std::uint32_t>(i));
              return;
            }
            // gw = g beta V_j: the factor per unit neighbour volume is gw / V_j.
            const double q = half_c * gw / ns.cur[4 * j + 3] * F / r;
            fac[k] = q;
            sum.add(q * ns.cur[4 * j + 3], d0, d1, d2, gw * phi * len);
          });
          sum.template store_forces<D>(ns, i);
          if (W) W[i] = 0.25 * ns.micromodulus[i] * sum.w;
        }
#pragma omp for schedule(dynamic, 512)
        for (std::size_t r = 0; r < n_rows; ++r) {
          const std::size_t i = split.at(r, true);
          if (!(ns.flags[i] & kActive)) continue;
          double acc[3] = {ns.f[0][i], ns.f[1][i], ns.f[2][i]};
          for (std::uint64_t t = bf.t_offsets[i]; t < bf.t_offsets[i + 1]; ++t) {
            const double qk = fac[bf.t_bond[t]];
            if (qk == 0.0) continue;
            const std::size_t o = bf.t_owner[t];
            const double fr = qk * ns.cur[4 * o + 3];
            for (int e = 0; e < D; ++e) acc[e] += fr * (ns.cur[4 * o + e] - ns.cur[4 * i + e]);
          }
          for (int e = 0; e < D; ++e) ns.f[e][i] = acc[e];
        }
#pragma omp critical(bond_law_dual_broken)
        newly.insert(newly.end(), mine.begin(), mine.end());
      }
      std::sort(newly.begin(), newly.end());
      for (const auto& [k, i] : newly) {
        ns.broken_weight[i] += static_cast<double>(bf.beta[k]) * ns.volume[bf.neighbor[k]];
        bf.beta[k] = -bf.beta[k];
        if (c.broken_log) c.broken_log->push_back(k);
      }
      return newly.size();
    }
  };

  template <int D, InfluenceShape S>
  struct Energy {
    static void run(const NodeSet& ns, const BondFamilies& bf, const BondLawCall& c,
                    std::vector<double>& W) {
      // With c.rows, only those rows; the others keep theirs.
      const std::size_t n = c.rows ? c.rows->size() : ns.size();
      if (c.rows) W.resize(ns.size(), 0.0);
      else W.assign(ns.size(), 0.0);
#pragma omp parallel for schedule(guided, 32)
      for (std::size_t q = 0; q < n; ++q) {
        const std::size_t i = c.rows ? (*c.rows)[q] : q;
        if (!(ns.flags[i] & kActive)) {
          W[i] = 0.0;
          continue;
        }
        const bool node_breaks = !(ns.flags[i] & kNoFail);
        const double b = ns.critical_stretch[i];
        double w = 0;
        for_intact<D, S>(ns, bf, i, [&](std::uint64_t k, std::size_t, double, double, double,
                                        double, double s, double gw, double len) {
          const bool law = node_breaks && bf.inv_length[k] > 0.0;
          const double phi = law ? L::energy(s, bf.state[k], c.onset_stretch, b) : s * s;
          w += gw * phi * len;
        });
        W[i] = 0.25 * ns.micromodulus[i] * w;
      }
    }
  };

  template <int D, InfluenceShape S>
  struct Stress {
    static void run(const NodeSet& ns, const BondFamilies& bf, const BondLawCall& c,
                    std::vector<double>& sigma) {
      sigma.assign(9 * ns.size(), 0.0);
#pragma omp parallel for schedule(guided, 32)
      for (std::size_t i = 0; i < ns.size(); ++i) {
        if (!(ns.flags[i] & kActive)) continue;
        const bool node_breaks = !(ns.flags[i] & kNoFail);
        const double b = ns.critical_stretch[i], ci = ns.micromodulus[i];
        double* out = sigma.data() + 9 * i;
        for_intact<D, S>(ns, bf, i, [&](std::uint64_t k, std::size_t j, double d0, double d1,
                                        double d2, double r, double s, double gw, double) {
          const bool law = node_breaks && bf.inv_length[k] > 0.0;
          const double F = law ? L::force(s, bf.state[k], c.onset_stretch, b) : s;
          // 1/2 f (x) xi, f = c g F beta V e, xi the reference bond vector
          const double y[3] = {d0, d1, d2};
          const double xi[3] = {ns.x[0][j] - ns.x[0][i], ns.x[1][j] - ns.x[1][i],
                                ns.x[2][j] - ns.x[2][i]};
          const double t = 0.5 * ci * gw * F / r;
          for (int p = 0; p < D; ++p)
            for (int q = 0; q < D; ++q) out[3 * p + q] += t * y[p] * xi[q];
        });
      }
    }
  };

  static std::size_t forces(NodeSet& ns, BondFamilies& bf, const BondLawCall& c) {
    // Rows the pass skips keep their energy and stretch; listed inactive rows hold none.
    const std::size_t n = c.rows ? c.rows->size() : ns.size();
    if (c.W) {
      if (c.rows) c.W->resize(ns.size(), 0.0);
      else c.W->assign(ns.size(), 0.0);
    }
    prepare_row_output(c.breakable_stretch, ns, c.rows, -INFINITY);
    for (std::size_t q = 0; c.W && q < n; ++q) {
      const std::size_t i = c.rows ? (*c.rows)[q] : q;
      if (!(ns.flags[i] & kActive)) (*c.W)[i] = 0.0;
    }
    return dispatch<Forces>(ns.dim, c.shape, ns, bf, c);
  }
  static std::size_t dual_forces(NodeSet& ns, BondFamilies& bf, const BondLawCall& c) {
    return dispatch<DualForces>(ns.dim, c.shape, ns, bf, c);
  }
  static void energy_density(const NodeSet& ns, const BondFamilies& bf, const BondLawCall& c,
                             std::vector<double>& W) {
    dispatch<Energy>(ns.dim, c.shape, ns, bf, c, W);
  }
  static void stress(const NodeSet& ns, const BondFamilies& bf, const BondLawCall& c,
                     std::vector<double>& sigma) {
    dispatch<Stress>(ns.dim, c.shape, ns, bf, c, sigma);
  }
};

// The registry entry of law L (constant-initialized: test tables read it before main), from its
// static members name, description, stress_key, stress_meaning, needs_fracture_energy and
// breaking_stretch(sb, onset).
template <class L>
constexpr BondLaw make_bond_law() {
  return BondLaw{L::name,          L::description,           L::stress_key,
                 L::stress_meaning, L::needs_fracture_energy, &L::breaking_stretch,
                 &BondLawKernels<L>::forces, &BondLawKernels<L>::dual_forces,
                 &BondLawKernels<L>::energy_density, &BondLawKernels<L>::stress};
}

}  // namespace periadapt
