// Elastic-perfectly-plastic bond (CabanaPD's ElasticPerfectlyPlastic PMB law): each bond keeps
// a plastic stretch s_p; it responds c (s - s_p) and flows once |s - s_p| reaches the yield
// stretch s_Y, in tension and in compression. It breaks at the total stretch s0 for which the
// work to break it, c xi s_Y (s0 - s_Y / 2), is the brittle bond's 1/2 c xi sb^2 at the G0
// critical stretch sb: s0 = sb^2 / (2 s_Y) + s_Y / 2 (CabanaPD's 3D formula in every dimension).
#include "material/bond_law_kernel.hpp"

namespace periadapt {

namespace {

struct ElasticPerfectlyPlastic {
  static constexpr std::string_view name = "elastic_perfectly_plastic";
  static constexpr std::string_view description =
      "bond-based, each bond elastic-perfectly plastic (plastic stretch per bond)";
  static constexpr std::string_view stress_key = "yield_stress";
  static constexpr std::string_view stress_meaning =
      "stress of an equal all-round stretch at which bonds yield (Pa)";
  static constexpr bool needs_fracture_energy = false;
  static double breaking_stretch(double sb, double sy) { return sb * sb / (2.0 * sy) + 0.5 * sy; }

  static double update(double s, double sp, double sy, double) {
    if (s >= sp + sy) return s - sy;
    if (s <= sp - sy) return s + sy;
    return sp;
  }
  static double force(double s, double sp, double, double) { return s - sp; }
  // The stored (recoverable) part; the plastic work is dissipated.
  static double energy(double s, double sp, double, double) { return (s - sp) * (s - sp); }
  static bool failed(double s, double, double s0) { return s > s0; }
};

}  // namespace

extern constinit const BondLaw kElasticPerfectlyPlastic = make_bond_law<ElasticPerfectlyPlastic>();

}  // namespace periadapt
