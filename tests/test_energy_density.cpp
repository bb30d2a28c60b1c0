// Homogeneous deformation: the strain-energy density of a bulk node equals the classical value
// (issue 2 acceptance: 2% at m = 3, 0.5% at m = 6) with accurate (sub-cell) partial volumes.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/energy.hpp"
#include "input/deck_builder.hpp"
#include "material/pmb.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"

using namespace periadapt;

namespace {

struct Case {
  int dim;
  PlaneCondition plane;
  double m;
};

// Builds a cube/square/bar of (2*m+9) cells per side, applies u = eps * x (isotropic) or
// u = (eps x, 0, 0) (uniaxial strain) and returns W at the centre node over the classical W.
double energy_ratio(const Case& c, bool isotropic, Quadrature q,
                    InfluenceShape shape = InfluenceShape::Constant) {
  const double dx = 1e-3, E = 1e9, eps = 1e-4;
  const int cells = 2 * static_cast<int>(std::ceil(c.m)) + 9;
  DeckBuilder d;
  d.set("model.dimension", c.dim);
  if (c.dim == 2) d.set("model.plane", c.plane == PlaneCondition::Stress ? "stress" : "strain");
  d.set("material.youngs_modulus", 1.0e9)
      .set("material.density", 1000.0)
      .set("material.micromodulus", to_string(shape))
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", c.m)
      .set("discretization.quadrature", q == Quadrature::Subcell ? "subcell" : "pa_pdlammps")
      .set("discretization.body.box.min", std::vector<double>(c.dim, 0.0))
      .set("discretization.body.box.max", std::vector<double>(c.dim, cells * dx))
      .set("damage.enabled", false)
      .set("solver.steps", 1);
  Model m = build_model(d.build("block"));
  NodeSet& ns = m.nodes;
  const double centre = 0.5 * cells * dx;
  std::size_t mid = 0;
  double best = 1e9;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    double r = 0;
    for (int d = 0; d < c.dim; ++d) r += std::pow(ns.x[d][i] - centre, 2);
    if (r < best) best = r, mid = i;
    for (int d = 0; d < c.dim; ++d) {
      ns.u[d][i] = (isotropic || d == 0) ? eps * ns.x[d][i] : 0.0;
    }
    ns.sync_current(i);
  }
  std::vector<double> W;
  pmb_energy_density(ns, m.bonds, shape, W);
  double classical;
  if (isotropic) {
    classical = classical_isotropic_energy(c.dim, c.plane, E, eps);
  } else {
    const double nu = bond_based_poisson(c.dim, c.plane);
    classical = 0.5 * p_wave_modulus(c.dim, c.plane, E, nu) * eps * eps;
  }
  return W[mid] / classical;
}

}  // namespace

TEST(EnergyDensity, IsotropicExpansionMatchesClassicalAtM3) {
  for (Case c : {Case{1, PlaneCondition::None, 3}, Case{2, PlaneCondition::Stress, 3},
                 Case{2, PlaneCondition::Strain, 3}, Case{3, PlaneCondition::None, 3}}) {
    const double r = energy_ratio(c, true, Quadrature::Subcell);
    EXPECT_NEAR(r, 1.0, 0.02) << "dim " << c.dim;
  }
}

TEST(EnergyDensity, IsotropicExpansionMatchesClassicalAtM6) {
  for (Case c : {Case{1, PlaneCondition::None, 6}, Case{2, PlaneCondition::Stress, 6},
                 Case{2, PlaneCondition::Strain, 6}, Case{3, PlaneCondition::None, 6}}) {
    const double r = energy_ratio(c, true, Quadrature::Subcell);
    EXPECT_NEAR(r, 1.0, 0.005) << "dim " << c.dim;
  }
}

TEST(EnergyDensity, UniaxialStrainGivesBondBasedPWaveModulus) {
  // Uniaxial strain probes the Poisson ratio fixed by the bond-based model (1/3 plane stress,
  // 1/4 otherwise): W = (lambda + 2 mu) eps^2 / 2. Its cos^4 moment has a larger lattice
  // quadrature error than isotropic expansion (2.3% at m = 3), which must shrink with m.
  for (Case c : {Case{2, PlaneCondition::Stress, 3}, Case{2, PlaneCondition::Strain, 3},
                 Case{3, PlaneCondition::None, 3}}) {
    const double e3 = std::abs(energy_ratio(c, false, Quadrature::Subcell) - 1.0);
    c.m = 6;
    const double e6 = std::abs(energy_ratio(c, false, Quadrature::Subcell) - 1.0);
    EXPECT_LT(e3, 0.03) << "dim " << c.dim;
    EXPECT_LT(e6, 0.01) << "dim " << c.dim;
  }
}

TEST(EnergyDensity, OtherInfluenceShapesConvergeAtSecondOrderInM) {
  // Non-constant shapes make the one-point rule err by O(1/m^2) (midpoint rule on a kink-free
  // integrand): the calibration is right if the error drops by ~4x from m = 6 to m = 12.
  for (InfluenceShape s : {InfluenceShape::Triangular, InfluenceShape::InvertedTriangular}) {
    for (Case c : {Case{1, PlaneCondition::None, 6}, Case{2, PlaneCondition::Stress, 6}}) {
      const double e6 = std::abs(energy_ratio(c, true, Quadrature::Subcell, s) - 1.0);
      c.m = 12;
      const double e12 = std::abs(energy_ratio(c, true, Quadrature::Subcell, s) - 1.0);
      EXPECT_LT(e6, 0.03) << to_string(s) << " dim " << c.dim;
      EXPECT_LT(e12, 0.4 * e6 + 1e-4) << to_string(s) << " dim " << c.dim;
    }
  }
}

TEST(EnergyDensity, PaPdlammpsUnderestimatesByItsKnownDeficit) {
  // PA-PDLAMMPS drops the cells cut by the horizon beyond |xi| = delta: at m = 3 the 2D lattice
  // sum of beta*|xi| is 0.869 of the continuous integral (hand sum over the 28 lattice offsets).
  const double r = energy_ratio({2, PlaneCondition::Stress, 3}, true, Quadrature::PaPdlammps);
  EXPECT_NEAR(r, 0.8690, 0.001);
}

TEST(EnergyDensity, ForcePassWithEnergiesGivesTheSameForcesBitForBit) {
  // The force pass sweeps each row once for forces and energy density when energies are asked
  // for (history samples, the energy trigger). Its forces and broken bonds must be exactly those
  // of the plain pass, so results do not depend on the output cadence; its densities those of
  // the separate energy pass, to round-off. Strains up to 3 s0 break bonds on the way.
  for (const char* shape : {"constant", "triangular"}) {
    Model a = build_model(DeckBuilder()
                              .set("model.dimension", 2)
                              .set("model.plane", "stress")
                              .set("material.youngs_modulus", 72.0e9)
                              .set("material.density", 2440.0)
                              .set("material.fracture_energy", 135.0)
                              .set("material.micromodulus", shape)
                              .set("discretization.spacing", 0.001)
                              .set("discretization.horizon_factor", 3.0)
                              .set("discretization.body.box.min", {0.0, 0.0})
                              .set("discretization.body.box.max", {0.03, 0.02})
                              .set("solver.steps", 1)
                              .build("strained plate"));
    NodeSet& ns = a.nodes;
    const double s0 = a.material.s0;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      const double x = ns.x[0][i], y = ns.x[1][i];
      ns.u[0][i] = 3 * s0 * 0.002 * std::tanh((x - 0.015) / 0.002) + 1e-7 * std::sin(300 * y);
      ns.u[1][i] = 0.5 * s0 * y * std::cos(200 * x);
      ns.sync_current(i);
    }
    Model b = a;
    std::vector<double> W;
    const std::size_t broken_a = internal_forces(a, true, nullptr, &W);
    const std::size_t broken_b = internal_forces(b, true, nullptr, nullptr);
    EXPECT_GT(broken_a, 100u) << shape;
    EXPECT_EQ(broken_a, broken_b) << shape;
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (int d = 0; d < 2; ++d) ASSERT_EQ(a.nodes.f[d][i], b.nodes.f[d][i]) << shape << " " << i;
    EXPECT_EQ(a.bonds.beta, b.bonds.beta) << shape;
    std::vector<double> W2;
    energy_density(b, W2);
    double wmax = 0;
    for (double w : W2) wmax = std::max(wmax, w);
    ASSERT_GT(wmax, 0.0);
    for (std::size_t i = 0; i < ns.size(); ++i) EXPECT_NEAR(W[i], W2[i], 1e-13 * wmax) << shape << " " << i;
  }
}
