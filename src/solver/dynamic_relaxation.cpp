#include "solver/dynamic_relaxation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "solver/internal_forces.hpp"

namespace periadapt {

namespace {

struct Fixed {
  std::uint32_t node;
  int comp;
  double value;  // at full load
};

}  // namespace

RelaxationStatus run_dynamic_relaxation(Model& m, const RelaxationOptions& opt,
                            const std::function<void(const RelaxationStepReport&)>& after_step) {
  NodeSet& ns = m.nodes;
  const int D = ns.dim;
  const std::size_t n = ns.size();
  std::vector<Fixed> fixed;
  std::vector<char> is_fixed(3 * n, 0);
  for (const PrescribedMotion& pm : m.motions)
    for (std::uint32_t i : pm.nodes)
      for (int d = 0; d < D; ++d)
        if (pm.component[d]) {
          const double val = pm.kind == PrescribedMotion::Kind::Displacement
                                 ? (*pm.component[d])(ns.x[0][i], ns.x[1][i], ns.x[2][i], 0.0)
                                 : 0.0;  // a prescribed velocity holds the node in a static run
          fixed.push_back({i, d, val});
          is_fixed[3 * i + d] = 1;
        }
  // Fictitious density: Gershgorin bound of the tangent stiffness row (unit pseudo time step).
  std::vector<double> K, lambda(n, 0.0);
  material_stiffness_sum(ns, m.bonds, material_context(m), K);
  for (std::size_t i = 0; i < n; ++i) lambda[i] = std::max(0.5 * D * K[i], 1e-300);

  std::vector<double> F_prev(3 * n, 0.0);
  std::array<std::vector<double>, 3> body;  // body-force densities at this load step
  for (int step = 1; step <= opt.load_steps; ++step) {
    const double lf = static_cast<double>(step) / opt.load_steps;
    RelaxationStepReport rep;
    rep.load_step = step;
    rep.load_factor = lf;
    for (auto& b : body) b.assign(n, 0.0);
    double bnorm = 0;
    for (const BodyLoad& L : m.loads) {
      const double amp = L.amplitude(1e300) * lf;
      for (std::uint32_t i : L.nodes)
        for (int d = 0; d < D; ++d) body[static_cast<std::size_t>(d)][i] += amp * L.density[static_cast<std::size_t>(d)];
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < D; ++d) bnorm += body[static_cast<std::size_t>(d)][i] * body[static_cast<std::size_t>(d)][i];
    bnorm = std::sqrt(bnorm);
    for (const Fixed& f : fixed) ns.u[f.comp][f.node] = lf * f.value;
    for (;;) {  // relax, break, relax again until no bond breaks
      for (int d = 0; d < 3; ++d) std::fill(ns.v[d].begin(), ns.v[d].end(), 0.0);
      ns.sync_all_current();
      bool first = true;
      double res = INFINITY, fnorm_ref = 0;
      long it = 0;
      for (; it < opt.max_iterations; ++it) {
        if (opt.stop_requested && it % 16 == 0 && opt.stop_requested())
          return RelaxationStatus::Interrupted;
        internal_forces(m, false);
        // Residual and the Rayleigh-quotient damping from the change of force.
        double num = 0, den = 0, fn = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (!(ns.flags[i] & kActive)) continue;
          for (int d = 0; d < D; ++d) {
            if (is_fixed[3 * i + d]) continue;
            const double F = ns.f[d][i] + body[static_cast<std::size_t>(d)][i];
            fn += F * F;
            const double v = ns.v[d][i];
            if (!first && v != 0.0) {
              const double kii = -(F - F_prev[3 * i + d]) / (lambda[i] * v);
              num += v * kii * v;
            }
            den += v * v;
            F_prev[3 * i + d] = F;
          }
        }
        fn = std::sqrt(fn);
        if (it == 0) fnorm_ref = std::max(bnorm, fn);
        // Pure displacement loading has no applied force: measure against the first residual.
        const double ref = bnorm > 0 ? bnorm : std::max(fnorm_ref, 1e-300);
        res = fn / ref;
        if (res <= opt.tolerance) break;
        double c = 0;
        if (!first && den > 0 && num > 0) c = std::min(2.0 * std::sqrt(num / den), 1.9);
        for (std::size_t i = 0; i < n; ++i) {
          if (!(ns.flags[i] & kActive)) continue;
          for (int d = 0; d < D; ++d) {
            if (is_fixed[3 * i + d]) continue;
            const double F = ns.f[d][i] + body[static_cast<std::size_t>(d)][i];
            double& v = ns.v[d][i];
            v = first ? 0.5 * F / lambda[i] : ((2.0 - c) * v + 2.0 * F / lambda[i]) / (2.0 + c);
            ns.u[d][i] += v;
          }
          ns.sync_current(i);
        }
        first = false;
      }
      rep.iterations += it;
      rep.residual = res;
      rep.converged = res <= opt.tolerance;
      if (!rep.converged) {
        after_step(rep);
        return RelaxationStatus::NotConverged;
      }
      if (!m.damage_enabled) break;
      const std::size_t broke = internal_forces(m, true);
      rep.newly_broken += broke;
      if (broke == 0) break;
    }
    after_step(rep);
  }
  return RelaxationStatus::Converged;
}

}  // namespace periadapt
