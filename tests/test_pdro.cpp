// Refinement overlay (Stewart & Jeon 2019): the PDDO interpolation is exact for quadratic fields,
// and the overlay raises the strength of a uniformly stretched body by sqrt(n).
#include <gtest/gtest.h>

#include <cmath>

#include "material/pmb.hpp"
#include "model/build_model.hpp"
#include "overlay/pddo.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

TEST(Pdro, PddoReproducesLinearAndQuadraticFields) {
  for (int dim : {2, 3}) {
    std::vector<PddoPoint> pts;
    const int r = 4;
    for (int i = -r; i <= r; ++i)
      for (int j = -r; j <= r; ++j)
        for (int k = (dim == 3 ? -r : 0); k <= (dim == 3 ? r : 0); ++k)
          if (i * i + j * j + k * k <= r * r) pts.push_back({{0.1 * i, 0.1 * j, 0.1 * k}, 1e-3});
    auto lin = [](const std::array<double, 3>& x) { return 0.3 + 2 * x[0] - x[1] + 0.5 * x[2]; };
    auto quad = [](const std::array<double, 3>& x) {
      return 1.0 + x[0] - 3 * x[1] + 4 * x[0] * x[0] - 2 * x[0] * x[1] + 5 * x[1] * x[1] +
             x[2] * (0.7 - x[0] + 2 * x[2] + 3 * x[1]);
    };
    for (const std::array<double, 3>& at : {std::array<double, 3>{0.033, -0.021, 0.0},
                                            std::array<double, 3>{-0.12, 0.05, dim == 3 ? 0.07 : 0.0}}) {
      std::vector<double> c;
      ASSERT_TRUE(pddo_weights(dim, at, pts, 0.4, c));
      double fl = 0, fq = 0;
      for (std::size_t k = 0; k < pts.size(); ++k) fl += c[k] * lin(pts[k].x), fq += c[k] * quad(pts[k].x);
      EXPECT_NEAR(fl, lin(at), 1e-10) << dim << "D";
      EXPECT_NEAR(fq, quad(at), 1e-10) << dim << "D";
    }
  }
}

namespace {

// Bonds broken by one force pass under a uniform strain eps along x, with or without the overlay.
std::size_t broken_under_uniform_strain(double eps, bool overlay) {
  const std::string yaml =
      "model: {dimension: 2, plane: strain}\n"
      "material: {youngs_modulus: 72.0e9, density: 2400, critical_stretch: 1.0e-3}\n"
      "discretization: {spacing: 0.001, horizon_factor: 4, body: {box: {min: [0, 0], max: [0.03, 0.02]}}}\n" +
      std::string(overlay ? "damage: {overlay: {n: 4}}\n" : "") + "solver: {steps: 1}\n";
  Model m = build_model(test::deck_from(yaml));
  NodeSet& ns = m.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    ns.u[0][i] = eps * ns.x[0][i];
    ns.sync_current(i);
  }
  return pmb_forces(ns, m.bonds, m.material.shape, true, nullptr, nullptr, &m.pdro).newly_broken;
}

}  // namespace

TEST(Pdro, OverlayRaisesTheStrengthOfAUniformFieldBySqrtN) {
  // A linear field has the same strain on the sub-grid as on the bond, so with n = 4 a bond only
  // breaks beyond 2 s0 (s0' = s0 sqrt(n)): at 1.5 s0 the plain model breaks the bonds along x,
  // the overlay keeps them; at 2.5 s0 both break.
  EXPECT_GT(broken_under_uniform_strain(1.5e-3, false), 0u);
  EXPECT_EQ(broken_under_uniform_strain(1.5e-3, true), 0u);
  EXPECT_GT(broken_under_uniform_strain(2.5e-3, true), 0u);
}
