// Bilinear softening bond: linear up to the peak stretch s_p, then a force falling linearly to
// zero at the final stretch s_f; unloading and reloading follow the secant to the origin, and
// compression keeps the full stiffness. The history is the largest stretch reached, k. The work
// to break a bond, 1/2 c xi s_p s_f, equals the brittle bond's 1/2 c xi sb^2 at the G0 critical
// stretch sb, so s_f = sb^2 / s_p and a crack dissipates G0 whatever s_p.
#include "material/bond_law_kernel.hpp"

namespace periadapt {

namespace {

struct BilinearSoftening {
  static constexpr std::string_view name = "bilinear_softening";
  static constexpr std::string_view description =
      "bond-based, each bond softening linearly from its peak (largest stretch per bond)";
  static constexpr std::string_view stress_key = "peak_stress";
  static constexpr std::string_view stress_meaning =
      "stress of an equal all-round stretch at which bonds start to soften (Pa)";
  static constexpr bool needs_fracture_energy = true;
  static double breaking_stretch(double sb, double sp) { return sb * sb / sp; }

  static double update(double s, double k, double, double) { return s > k ? s : k; }
  static double force(double s, double k, double sp, double sf) {
    if (s <= 0.0 || k <= sp) return s;
    // Secant stiffness of the envelope point (k, sp (sf - k) / (sf - sp)).
    return s * sp * std::max(0.0, sf - k) / (k * (sf - sp));
  }
  static double energy(double s, double k, double sp, double sf) {
    return s * force(s, k, sp, sf);
  }
  static bool failed(double, double k, double sf) { return k >= sf; }
};

}  // namespace

extern constinit const BondLaw kBilinearSoftening = make_bond_law<BilinearSoftening>();

}  // namespace periadapt
