// The bilinear softening bond law (material/bilinear_softening.cpp) against hand calculations on
// a 1D bar stretched homogeneously (every bond at the same stretch, tension = K s on the elastic
// branch): the envelope rises to K s_p and falls linearly to zero at s_f = sb^2 / s_p; unloading
// and reloading follow the secant to the origin; compression keeps K; and the work along the
// envelope, K s_p s_f / 2, is the brittle bar's K sb^2 / 2, the G0 calibration.
// tests/cli_bond_laws.sh measures the energy a crack dissipates in an explicit run.
// Exact relations are held to 1e-9: a stretch formed from positions carries a relative
// round-off of about 1e-12 at s ~ 1e-3.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

Model bar() {
  return build_model(DeckBuilder()
                         .set("model.dimension", 1)
                         .set("model.thickness", 1.0e-4)
                         .set("model.formulation", "bilinear_softening")
                         .set("material.youngs_modulus", 1.0e9)
                         .set("material.density", 1000.0)
                         .set("material.fracture_energy", 100.0)
                         .set("material.peak_stress", 1.0e6)
                         .set("discretization.spacing", 0.0005)
                         .set("discretization.horizon_factor", 4.0)
                         .set("discretization.body.box.min", {0.0})
                         .set("discretization.body.box.max", {0.04})
                         .set("solver.steps", 1)
                         .build("softening bar"));
}

double tension(Model& m, double s) { return test::bar_tension(m, s, 0.04); }

}  // namespace

TEST(BilinearSoftening, EnvelopeSecantUnloadingAndFailureFollowTheHandCalculation) {
  Model m = bar();
  const double sp = m.material.onset_stretch, sf = m.material.s0;
  ASSERT_DOUBLE_EQ(sp, 1e6 / 1e9);
  const double sb = critical_stretch_from_g0(1, InfluenceShape::Constant, m.material.c0,
                                             m.horizon, 1e-4, 100.0);
  EXPECT_NEAR(sf, sb * sb / sp, 1e-15);
  const double K = tension(m, 0.5 * sp) / (0.5 * sp);
  EXPECT_NEAR(tension(m, sp) / (K * sp), 1.0, 1e-9);  // the peak
  // Softening branch: linear to zero at s_f.
  const double s1 = sp + 0.5 * (sf - sp);
  EXPECT_NEAR(tension(m, s1) / (0.5 * K * sp), 1.0, 1e-9);
  // Unloading along the secant of (s1, K sp / 2): no permanent set, no new history.
  const double secant = 0.5 * K * sp / s1;
  for (double s : {0.75 * s1, 0.3 * s1, 0.0, 0.5 * s1, s1})
    EXPECT_NEAR(tension(m, s), secant * s, 1e-9 * K * sp) << s;
  // Compression keeps the undamaged stiffness.
  EXPECT_NEAR(tension(m, -0.5 * sp) / (-0.5 * K * sp), 1.0, 1e-9);
  // Back on the envelope beyond s1, then past s_f every breakable bond is broken.
  const double s2 = sp + 0.9 * (sf - sp);
  EXPECT_NEAR(tension(m, s2) / (0.1 * K * sp), 1.0, 1e-9);
  EXPECT_EQ(tension(m, 1.0001 * sf), 0.0);
  for (std::size_t k = 0; k < m.bonds.beta.size(); ++k)
    if (m.bonds.breakable(k)) {
      ASSERT_LT(m.bonds.beta[k], 0.0f);
    }
}

TEST(BilinearSoftening, WorkAlongTheEnvelopeIsTheBrittleBondsWork) {
  Model m = bar();
  const double sp = m.material.onset_stretch, sf = m.material.s0;
  const double sb = std::sqrt(sp * sf);
  const int n = 2000;
  double work = 0, prev = 0;
  for (int k = 1; k <= n; ++k) {  // trapezoid rule: exact on the piecewise linear envelope
    const double s = sf * k / n, p = tension(m, s);
    work += 0.5 * (prev + p) * (sf / n);
    prev = p;
  }
  Model e = bar();
  const double K = tension(e, 0.5 * sp) / (0.5 * sp);
  // The kink at s_p falls inside one interval: that interval's trapezoid misses at most
  // K sp (sf / n) / 4 of the area.
  EXPECT_NEAR(work / (0.5 * K * sb * sb), 1.0, 0.5 / n);
}
