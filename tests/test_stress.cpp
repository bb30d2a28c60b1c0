// Per-node stress and strain (the VTU's `stress` and `strain`): under a homogeneous strain the
// fitted strain is the applied one, and the stress, being the derivative of the node's energy
// density, is the classical C : eps wherever that energy density is classical.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"
#include "core/visible_gradient.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

struct Case {
  int dim;
  std::string plane;  // "stress", "strain" or "" (3D)
  std::string formulation;
  double nu;  // LPS: the deck's; PMB: the bond-based model's own
};

void classical_stress(const Case& c, double E, const double eps[3][3], double sig[3][3]) {
  const double mu = E / (2 * (1 + c.nu));
  double lambda = E * c.nu / ((1 + c.nu) * (1 - 2 * c.nu));
  if (c.dim == 2 && c.plane == "stress") lambda = 2 * lambda * mu / (lambda + 2 * mu);
  double tr = 0;
  for (int a = 0; a < c.dim; ++a) tr += eps[a][a];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      sig[a][b] = a < c.dim && b < c.dim ? 2 * mu * eps[a][b] + (a == b ? lambda * tr : 0.0) : 0.0;
}

struct Errors {
  double stress = 0, strain = 0;
  std::size_t nodes = 0;
};

// Worst relative stress error (against the largest classical component) and worst absolute
// strain error (against g) over the nodes within `margin` horizons of at most `cut` faces.
Errors worst_errors(const Case& c, const std::string& correction, double margin, int cut) {
  const double E = 70e9, dx = 0.01, delta = 3 * dx;
  const double hi[3] = {0.16, 0.14, c.dim == 3 ? 0.13 : 0.0};
  DeckBuilder d;
  d.set("model.dimension", c.dim);
  if (c.dim == 2) d.set("model.plane", c.plane);
  d.set("model.formulation", c.formulation)
      .set("material.youngs_modulus", 70.0e9)
      .set("material.density", 2700.0);
  if (c.formulation == "lps") d.set("material.poisson_ratio", c.nu);
  d.set("discretization.spacing", dx)
      .set("discretization.surface_correction", correction)
      .set("discretization.body.box.min", std::vector<double>(c.dim, 0.0))
      .set("discretization.body.box.max", std::vector<double>(hi, hi + c.dim))
      .set("damage.enabled", false)
      .set("solver.steps", 1);
  Model md = build_model(d.build("block"));
  const double g = 1e-7;
  const double strains[3][3][3] = {{{g, 0, 0}, {0, -0.3 * g, 0}, {0, 0, 0.2 * g}},
                                   {{0.3 * g, g, 0}, {g, -0.2 * g, 0.5 * g}, {0, 0.5 * g, g}},
                                   {{0, 0.4 * g, -g}, {0.4 * g, 0, 0.8 * g}, {-g, 0.8 * g, 0}}};
  Errors err;
  NodeSet& ns = md.nodes;
  for (const auto& eps : strains) {
    test::apply_homogeneous_strain(ns, eps);
    std::vector<double> sigma;
    stress_density(md, sigma);
    double sc[3][3], scale = 0;
    classical_stress(c, E, eps, sc);
    for (auto& row : sc)
      for (double v : row) scale = std::max(scale, std::abs(v));
    err.nodes = 0;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      int near = 0;
      for (int d = 0; d < c.dim; ++d)
        near += ns.x[d][i] < margin * delta || ns.x[d][i] > hi[d] - margin * delta;
      if (near > cut) continue;
      ++err.nodes;
      double G[3][3];
      fit_gradient(ns, md.bonds, static_cast<std::uint32_t>(i), ns.u, G);
      for (int a = 0; a < c.dim; ++a)
        for (int b = 0; b < c.dim; ++b) {
          err.stress = std::max(err.stress, std::abs(sigma[9 * i + 3 * a + b] - sc[a][b]) / scale);
          err.strain = std::max(err.strain, std::abs(0.5 * (G[a][b] + G[b][a]) - eps[a][b]) / g);
        }
    }
  }
  return err;
}

}  // namespace

// LPS with the moments correction has the classical energy density at every node but the
// corners' (test_lps), so its stress is C : eps there, edge nodes included: bound 1e-3, the
// correction's convergence (bond factors settle to 1e-5). Uncorrected, the surface nodes' stress
// is off by more than 10%.
TEST(Stress, LpsStressIsClassicalUpToTheSurfaceWithTheMomentsCorrection) {
  for (const Case& c : {Case{2, "stress", "lps", 0.25}, Case{2, "strain", "lps", 0.3},
                        Case{3, "", "lps", 0.2}}) {
    // Every node whose family one face cuts at most (corner families cannot be made isotropic).
    const Errors inner = worst_errors(c, "moments", 1.0, 1);
    EXPECT_LT(inner.stress, 1e-3) << c.dim << "D " << c.plane;
    EXPECT_LT(inner.strain, 1e-9) << c.dim << "D " << c.plane;
    EXPECT_GT(inner.nodes, 10u);
    const Errors plain_surface = worst_errors(c, "false", 1.0, 1);
    EXPECT_GT(plain_surface.stress, 0.1) << c.dim << "D " << c.plane;
    std::printf("%dD %s LPS: stress error %.2e (edge and bulk), strain %.1e; uncorrected surface %.2e\n",
                c.dim, c.plane.c_str(), inner.stress, inner.strain, plain_surface.stress);
  }
}

// PMB's bond-based stress 1/2 sum f (x) xi: the classical stress of the bond-based Poisson
// ratio (1/3 plane stress, 1/4 otherwise) in the bulk, two horizons from the faces, with the
// moments correction. Bound 2e-3: the bond-based correction matches the even moments only, and
// the factors of neighbours nearer the surface leave small odd ones (measured 8e-4). The
// uncorrected m = 3 lattice (PA quadrature) is off by more than 5% for these strains: its
// calibration is exact for isotropic expansion only.
TEST(Stress, PmbBondStressIsClassicalInTheBulk) {
  for (const Case& c : {Case{2, "stress", "pmb", 1.0 / 3.0}, Case{2, "strain", "pmb", 0.25},
                        Case{3, "", "pmb", 0.25}}) {
    const Errors corrected = worst_errors(c, "moments", 2.0, 0);
    const Errors plain = worst_errors(c, "false", 2.0, 0);
    EXPECT_LT(corrected.stress, 2e-3) << c.dim << "D " << c.plane;
    EXPECT_GT(plain.stress, 0.05) << c.dim << "D " << c.plane;
    EXPECT_LT(corrected.strain, 1e-9);
    EXPECT_GT(corrected.nodes, 4u);
    std::printf("%dD %s PMB: stress error %.2e corrected, %.2e plain (bulk)\n", c.dim,
                c.plane.c_str(), corrected.stress, plain.stress);
  }
}
