// Micromodulus and critical-stretch calibration against the closed forms of the seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "input/deck_builder.hpp"
#include "material/micromodulus.hpp"
#include "setup/build_model.hpp"

using namespace periadapt;
constexpr double pi = std::numbers::pi;

TEST(Micromodulus, ConstantShapeMatchesThesisEq213) {
  const double E = 72e9, d = 1.5e-3, t = 0.01;
  // thesis Eq. 2.13a-c (b, c per unit thickness there; ours divides the thickness out)
  EXPECT_NEAR(micromodulus_c0(3, PlaneCondition::None, InfluenceShape::Constant, E, d, 1),
              12 * E / (pi * std::pow(d, 4)), 1e-9 * 12 * E / (pi * std::pow(d, 4)));
  EXPECT_NEAR(micromodulus_c0(2, PlaneCondition::Stress, InfluenceShape::Constant, E, d, t),
              9 * E / (pi * std::pow(d, 3) * t), 1e-6 * 9 * E / (pi * std::pow(d, 3) * t));
  EXPECT_NEAR(micromodulus_c0(2, PlaneCondition::Strain, InfluenceShape::Constant, E, d, 1),
              48 * E / (5 * pi * std::pow(d, 3)), 1e-6 * 48 * E / (5 * pi * std::pow(d, 3)));
  // Table 6.1 of the thesis: c = 61.10e18 and 7.64e18 N/m^6 (t = 1)
  EXPECT_NEAR(micromodulus_c0(2, PlaneCondition::Stress, InfluenceShape::Constant, E, d, 1) / 1e18,
              61.10, 0.02);  // the thesis prints 3 significant digits after rounding down
  EXPECT_NEAR(micromodulus_c0(2, PlaneCondition::Stress, InfluenceShape::Constant, E, 3e-3, 1) / 1e18,
              7.64, 0.01);
}

TEST(Micromodulus, OneDimensionalShapesMatchBobaru2009) {
  const double E = 1.0, d = 0.5, A = 2.0;
  // Bobaru et al. 2009 Eqs. 14, 18, 21
  EXPECT_NEAR(micromodulus_c0(1, PlaneCondition::None, InfluenceShape::Constant, E, d, A),
              2 * E / (d * d * A), 1e-12);
  EXPECT_NEAR(micromodulus_c0(1, PlaneCondition::None, InfluenceShape::Triangular, E, d, A),
              6 * E / (d * d * A), 1e-12);
  EXPECT_NEAR(micromodulus_c0(1, PlaneCondition::None, InfluenceShape::InvertedTriangular, E, d, A),
              3 * E / (d * d * A), 1e-12);
}

TEST(Micromodulus, ConicalPlaneStressMatchesMscEq9) {
  // MSc Eq. 9-10: c1 = 24E/(pi delta^3 (1-nu)), nu = 1/3
  const double E = 1e9, d = 2e-3;
  EXPECT_NEAR(micromodulus_c0(2, PlaneCondition::Stress, InfluenceShape::Triangular, E, d, 1),
              24 * E / (pi * std::pow(d, 3) * (2.0 / 3.0)), 1e-6 * 36 * E / (pi * std::pow(d, 3)));
}

TEST(CriticalStretch, MatchesThesisEq215) {
  const double E = 72e9, G0 = 135, d = 1.5e-3;
  auto s0 = [&](int dim, PlaneCondition pc) {
    const double c0 = micromodulus_c0(dim, pc, InfluenceShape::Constant, E, d, 1.0);
    return critical_stretch_from_g0(dim, InfluenceShape::Constant, c0, d, 1.0, G0);
  };
  EXPECT_NEAR(s0(3, PlaneCondition::None), std::sqrt(5 * G0 / (6 * E * d)), 1e-12);
  EXPECT_NEAR(s0(2, PlaneCondition::Stress), std::sqrt(4 * pi * G0 / (9 * E * d)), 1e-12);
  EXPECT_NEAR(s0(2, PlaneCondition::Strain), std::sqrt(5 * pi * G0 / (12 * E * d)), 1e-12);
  // Table 6.1: s0 = 1.32e-3 (dX = 0.5 mm) and 0.93e-3 (1 mm)
  EXPECT_NEAR(s0(2, PlaneCondition::Stress), 1.32e-3, 0.005e-3);
  // MSc Eq. 17, conical micromodulus in plane stress: s0 = sqrt(5 pi G0 / (9 E delta))
  const double c1 = micromodulus_c0(2, PlaneCondition::Stress, InfluenceShape::Triangular, E, d, 1);
  EXPECT_NEAR(critical_stretch_from_g0(2, InfluenceShape::Triangular, c1, d, 1, G0),
              std::sqrt(5 * pi * G0 / (9 * E * d)), 1e-12);
}

// The critical stretch a deck's fracture energy gives, checked against its definition rather than
// the closed forms: breaking every bond that crosses a plane, each at its micropotential
// c(xi) s0^2 xi / 2, must take G0 per unit crack area. The integral over the bonds crossing the
// plane (a point at depth z below it, partners at distance xi in the cap beyond it) is summed
// numerically for 1D, 2D and 3D and two influence shapes, with c0 and s0 as the model built them.
TEST(CriticalStretch, BreakingEveryBondAcrossAPlaneTakesTheFractureEnergy) {
  const double G0 = 135, delta = 3e-3, area = 2e-4, thickness = 5e-3;
  for (int dim : {1, 2, 3})
    for (const char* shape : {"constant", "triangular"}) {
      SCOPED_TRACE(std::to_string(dim) + "D " + shape);
      DeckBuilder d;
      d.set("model.dimension", dim);
      if (dim < 3) d.set("model.thickness", dim == 1 ? area : thickness);
      d.set("material.youngs_modulus", 72.0e9)
          .set("material.density", 2440.0)
          .set("material.fracture_energy", 135.0)
          .set("material.micromodulus", shape)
          .set("discretization.spacing", 1.0e-3)
          .set("discretization.horizon_factor", 3.0)
          .set("discretization.body.box.min", std::vector<double>(dim, 0.0))
          .set("discretization.body.box.max", std::vector<double>(dim, 0.01))
          .set("solver.steps", 1);
      const Model md = build_model(d.build("block"));
      const double c0 = md.nodes.micromodulus[0], s0 = md.nodes.critical_stretch[0];
      const bool tri = std::string(shape) == "triangular";
      auto w = [&](double xi) { return c0 * (tri ? 1 - xi / delta : 1.0) * s0 * s0 * xi / 2; };
      // Partners of a point at depth z, at distance xi beyond the plane: 1D one, 2D the arc
      // 2 xi acos(z/xi), 3D the cap 2 pi xi^2 (1 - z/xi).
      auto measure = [&](double z, double xi) {
        if (dim == 1) return 1.0;
        if (dim == 2) return 2 * xi * std::acos(z / xi);
        return 2 * pi * xi * xi * (1 - z / xi);
      };
      const int n = 1500;
      double G = 0;
      for (int a = 0; a < n; ++a) {
        const double z = (a + 0.5) * delta / n;
        const double h = (delta - z) / n;
        for (int b = 0; b < n; ++b) {
          const double xi = z + (b + 0.5) * h;
          G += w(xi) * measure(z, xi) * h * (delta / n);
        }
      }
      // Per unit crack area: 1D bonds act across the cross-section, 2D across the thickness.
      if (dim == 1) G *= area;
      if (dim == 2) G *= thickness;
      EXPECT_NEAR(G / G0, 1.0, 2e-4);
    }
}
