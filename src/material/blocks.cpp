#include "material/blocks.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

namespace {

double harmonic(double a, double b) { return 2.0 * a * b / (a + b); }

// The brittle critical stretch of `law` with fracture energy G0 at horizon delta.
double stretch_of(const MaterialLaw& law, int dim, bool state_based, double delta, double G0) {
  if (state_based) return lps_critical_stretch(dim, law.lps_constants, delta, G0);
  const double c0 = micromodulus_c0(dim, law.plane, law.shape, law.bb_equivalent_E, delta, law.thickness);
  return critical_stretch_from_g0(dim, law.shape, c0, delta, law.thickness, G0);
}

// The critical stretch of a bond between a and b at horizon delta.
double joint_stretch(const MaterialLaw& a, const MaterialLaw& b, int dim, bool state_based,
                     double delta) {
  if (!(a.G0 > 0) || !(b.G0 > 0)) return std::min(a.s0, b.s0);
  MaterialLaw joint = a;
  joint.bb_equivalent_E = harmonic(a.bb_equivalent_E, b.bb_equivalent_E);
  joint.lps_constants.kappa = harmonic(a.lps_constants.kappa, b.lps_constants.kappa);
  joint.lps_constants.mu = harmonic(a.lps_constants.mu, b.lps_constants.mu);
  return stretch_of(joint, dim, state_based, delta, std::min(a.G0, b.G0));
}

}  // namespace

BlockPairs block_pair_rules(const std::vector<MaterialLaw>& laws, int dim, bool state_based,
                            double delta) {
  BlockPairs p;
  p.count = laws.size();
  if (!p.active()) return p;
  const std::size_t n = p.count;
  p.stiffness.assign(n * n, 1.0);
  p.inv_stretch.assign(n * n, 1.0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b) continue;  // exactly 1: one block runs as one material does
      const MaterialLaw &la = laws[a], &lb = laws[b];
      p.stiffness[a * n + b] = 2.0 * lb.bb_equivalent_E / (la.bb_equivalent_E + lb.bb_equivalent_E);
      // Both in the same form at the deck's horizon (every form scales as delta^-1/2).
      const double sa = la.G0 > 0 ? stretch_of(la, dim, state_based, delta, la.G0) : la.s0;
      const double sab = joint_stretch(la, lb, dim, state_based, delta);
      // A node that cannot break its bonds (s0 = inf) keeps them whatever the far block.
      if (std::isfinite(sa) && std::isfinite(sab) && sab > 0) p.inv_stretch[a * n + b] = sa / sab;
    }
  return p;
}

}  // namespace periadapt
