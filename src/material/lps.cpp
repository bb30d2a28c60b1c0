#include "material/lps.hpp"

#include <cmath>

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

inline double omega(InfluenceShape s, double t) { return influence(s, t < 1.0 ? t : 1.0); }

// Pass 1: weighted volume (all bonds) and dilatation (intact bonds) of every active node.
void dilatation(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape, int D,
                LpsScratch& sc) {
  const std::size_t n = ns.size();
  sc.m.assign(n, 0.0);
  sc.theta.assign(n, 0.0);
  const double* yp = ns.cur.data();
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double inv_delta = 1.0 / ns.horizon[i];
    double m = 0, th = 0;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const std::size_t j = 4 * static_cast<std::size_t>(bf.neighbor[k]);
      const double x = bf.length(k);
      double r2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        const double t = yp[j + d] - yp[4 * i + d];
        r2 += t * t;
      }
      const double b = bf.beta[k];
      const double wv = omega(shape, x * inv_delta) * std::abs(b) * yp[j + 3];
      m += wv * x * x;
      if (b > 0) th += wv * x * (std::sqrt(r2) - x);
    }
    sc.m[i] = m;
    sc.theta[i] = m > 0 ? D * th / m : 0.0;
  }
}

}  // namespace

std::size_t lps_forces(NodeSet& ns, BondFamilies& bf, InfluenceShape shape, const LpsConstants& c,
                       bool allow_breaking, LpsScratch& sc, std::vector<std::uint64_t>* log,
                       std::vector<double>* Wout) {
  dilatation(ns, bf, shape, c.D, sc);
  const std::size_t n = ns.size();
  const double* yp = ns.cur.data();
  const double Dk = c.D * c.kappa, am = c.alpha * c.mu, invD = 1.0 / c.D;
  if (Wout) Wout->assign(n, 0.0);
  std::size_t broken_total = 0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : broken_total)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double mi = sc.m[i], thi = sc.theta[i];
    if (!(mi > 0)) {
      for (int d = 0; d < ns.dim; ++d) ns.f[d][i] = 0.0;
      continue;
    }
    const double s0 = (allow_breaking && !(ns.flags[i] & kNoFail)) ? ns.critical_stretch[i] : INFINITY;
    const double inv_di = 1.0 / ns.horizon[i];
    double a[3] = {0, 0, 0}, wdev = 0, bw = 0;
    std::size_t nb = 0;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const float b = bf.beta[k];
      if (!(b > 0.0f)) continue;
      const std::uint32_t jj = bf.neighbor[k];
      const std::size_t j = 4 * static_cast<std::size_t>(jj);
      const double x = bf.length(k);
      double dv[3] = {0, 0, 0}, r2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        dv[d] = yp[j + d] - yp[4 * i + d];
        r2 += dv[d] * dv[d];
      }
      const double r = std::sqrt(r2), e = r - x;
      const double V = yp[j + 3] * static_cast<double>(b);
      if (bf.inv_length[k] > 0.0 && e > s0 * x) {
        bf.beta[k] = -b;
        bw += V;
        ++nb;
        if (log) {
#pragma omp critical(lps_broken_log)
          log->push_back(k);
        }
        continue;
      }
      const double wi = omega(shape, x * inv_di);
      const double wj = omega(shape, x / ns.horizon[jj]);
      const double mj = sc.m[jj], thj = sc.theta[jj];
      const double edi = e - thi * x * invD;
      const double ti = (Dk * thi * wi * x + am * wi * edi) / mi;
      const double tj = mj > 0 ? (Dk * thj * wj * x + am * wj * (e - thj * x * invD)) / mj : 0.0;
      const double fr = (ti + tj) * V / r;
      for (int d = 0; d < ns.dim; ++d) a[d] += fr * dv[d];
      wdev += wi * edi * edi * V;
    }
    if (nb) ns.broken_weight[i] += bw;
    broken_total += nb;
    for (int d = 0; d < ns.dim; ++d) ns.f[d][i] = a[d];
    if (Wout) (*Wout)[i] = 0.5 * c.kappa * thi * thi + 0.5 * am / mi * wdev;
  }
  return broken_total;
}

void lps_energy_density(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                        const LpsConstants& c, LpsScratch& sc, std::vector<double>& W) {
  dilatation(ns, bf, shape, c.D, sc);
  const std::size_t n = ns.size();
  W.assign(n, 0.0);
  const double* yp = ns.cur.data();
  const double am = c.alpha * c.mu, invD = 1.0 / c.D;
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive) || !(sc.m[i] > 0)) continue;
    const double inv_di = 1.0 / ns.horizon[i];
    double wdev = 0;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      const float b = bf.beta[k];
      if (!(b > 0.0f)) continue;
      const std::size_t j = 4 * static_cast<std::size_t>(bf.neighbor[k]);
      const double x = bf.length(k);
      double r2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        const double t = yp[j + d] - yp[4 * i + d];
        r2 += t * t;
      }
      const double ed = std::sqrt(r2) - x - sc.theta[i] * x * invD;
      wdev += omega(shape, x * inv_di) * ed * ed * yp[j + 3] * static_cast<double>(b);
    }
    W[i] = 0.5 * c.kappa * sc.theta[i] * sc.theta[i] + 0.5 * am / sc.m[i] * wdev;
  }
}

}  // namespace periadapt
