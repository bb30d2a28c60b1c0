// Partial-volume quadrature: the analytic (IPA-Hybrid) areas cover the horizon exactly, the
// PA-PDLAMMPS rule by its known linear approximation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "discretize/lattice_moment.hpp"
#include "discretize/partial_volume.hpp"
#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "studies/weak_directions.hpp"

using namespace periadapt;

namespace {

// Sum of beta_j V_j over the family of the node nearest the body centre, plus its own cell.
double covered_area(const std::string& quadrature, double m, double rotation_deg) {
  Model md = build_model(DeckBuilder()
                             .set("model.dimension", 2)
                             .set("model.plane", "stress")
                             .set("material.youngs_modulus", 1.0)
                             .set("material.density", 1.0)
                             .set("discretization.spacing", 0.1)
                             .set("discretization.horizon_factor", m)
                             .set("discretization.quadrature", quadrature)
                             .set("discretization.rotation_deg", rotation_deg)
                             .set("discretization.body.box.min", {-2.05, -2.05})
                             .set("discretization.body.box.max", {2.05, 2.05})
                             .set("damage.enabled", false)
                             .set("solver.steps", 1)
                             .build("square"));
  const NodeSet& ns = md.nodes;
  std::size_t c = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (std::hypot(ns.x[0][i], ns.x[1][i]) < std::hypot(ns.x[0][c], ns.x[1][c])) c = i;
  double a = ns.volume[c];
  for (std::uint64_t k = md.bonds.begin(c); k < md.bonds.end(c); ++k)
    a += static_cast<double>(md.bonds.beta[k]) * ns.volume[md.bonds.neighbor[k]];
  return a;
}

}  // namespace

TEST(Quadrature, DiskRectangleAreaMatchesClosedForms) {
  const double R = 1.3;
  EXPECT_NEAR(disk_rectangle_area(-2, 2, -2, 2, R), M_PI * R * R, 1e-14);       // whole disk
  EXPECT_NEAR(disk_rectangle_area(0, 2, 0, 2, R), 0.25 * M_PI * R * R, 1e-14);  // quadrant
  EXPECT_NEAR(disk_rectangle_area(-2, 2, 0, 2, R), 0.5 * M_PI * R * R, 1e-14);  // half
  EXPECT_NEAR(disk_rectangle_area(-0.3, 0.4, -0.2, 0.5, R), 0.7 * 0.7, 1e-14);  // inside
  EXPECT_EQ(disk_rectangle_area(1.3, 2, -1, 1, R), 0.0);                        // outside
  // Circular segment beyond x = d: R^2 acos(d/R) - d sqrt(R^2 - d^2).
  const double d = 0.9;
  EXPECT_NEAR(disk_rectangle_area(d, 5, -5, 5, R),
              R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d), 1e-13);
}

TEST(Quadrature, IpaHybridAreasCoverTheHorizonExactly) {
  // Seleson's analytic areas: a bulk node's family plus its own cell cover pi delta^2 (thickness
  // 1), for integer and off-lattice m, on straight and rotated lattices.
  for (double m : {2.5, 3.0, 3.015, 3.3, 4.0, 4.7, 6.0})
    for (double rot : {0.0, 17.0}) {
      const double delta = 0.1 * m;
      // beta is stored in single precision: 1e-7 per cell, averaged over the cut cells.
      EXPECT_NEAR(covered_area("ipa_hybrid", m, rot) / (M_PI * delta * delta), 1.0, 1e-7)
          << "m = " << m << ", rotation " << rot;
    }
}

TEST(Quadrature, IpaHybridRuleCoversTheHorizonToRoundOff) {
  // The rule itself, in double precision (the bond arrays then store it in float, above): the
  // covered parts of every lattice cell around a bulk node sum to pi delta^2 within 1e-10
  // relative (issue 3 acceptance), on straight and rotated lattices, integer and off-lattice m.
  const double dx = 0.1;
  for (double m : {2.5, 3.0, 3.015, 3.3, 4.0, 4.7, 6.0})
    for (double rot_deg : {0.0, 17.0, 45.0}) {
      const double delta = m * dx, rot = rot_deg * M_PI / 180.0;
      const double c = std::cos(rot), s = std::sin(rot);
      const int K = static_cast<int>(std::ceil(m)) + 2;
      double area = 0;
      for (int i = -K; i <= K; ++i)
        for (int j = -K; j <= K; ++j) {
          const std::array<double, 3> off{dx * (c * i - s * j), dx * (s * i + c * j), 0.0};
          area += subcell_fraction(2, off, delta, dx, rot) * dx * dx;
        }
      EXPECT_NEAR(area / (M_PI * delta * delta), 1.0, 1e-10) << "m = " << m << ", rotation " << rot_deg;
    }
}

TEST(Quadrature, PaPdlammpsCoversItsLinearRuleNotTheDisk) {
  // Hand enumeration of the PA-PDLAMMPS rule (thesis Fig. 3.1a) at m = 3 on the unit lattice:
  // beta = 1 up to m - 1/2, (m + 1/2 - r) up to m, nothing beyond.
  const double m = 3.0;
  double expect = 1.0;  // own cell
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) {
      const double r = std::hypot(i, j);
      if ((i == 0 && j == 0) || r > m) continue;
      expect += r <= m - 0.5 ? 1.0 : m + 0.5 - r;
    }
  const double got = covered_area("pa_pdlammps", m, 0.0) / 0.01;
  EXPECT_NEAR(got, expect, 1e-5);
  EXPECT_GT(std::abs(got - M_PI * m * m) / (M_PI * m * m), 0.01);  // the known deficit
  RecordProperty("pa_pdlammps_over_disk", std::to_string(got / (M_PI * m * m)));
}

TEST(Quadrature, WeakBondDirectionsFollowTheFamilyOfEachRule) {
  // Thesis 5.2 for m = 3: the bond directions are atan(b / a) of the lattice vectors (a, b) in a
  // family. PA-PDLAMMPS keeps |xi| <= 3 dX: (1,0), (2,1), (1,1), (1,2), (0,1) and multiples.
  // IPA-Hybrid also keeps cells the horizon only partly covers, (3,1) and (3,2) (their nearest
  // corners are 2.55 and 2.92 dX away): 18.435, 33.690 and their complements. The thesis' printed
  // 30.964 deg (tan = 3/5) belongs to no m = 3 family; it first appears at m = 6 (vector (5,3)).
  auto near = [](const std::vector<double>& got, const std::vector<double>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < want.size(); ++k) EXPECT_NEAR(got[k], want[k], 1e-3) << k;
  };
  near(weak_directions_deg(3.0, "pa_pdlammps"), {0.0, 26.565, 45.0, 63.435, 90.0});
  near(weak_directions_deg(3.0, "ipa_hybrid"),
       {0.0, 18.435, 26.565, 33.690, 45.0, 56.310, 63.435, 71.565, 90.0});
  const std::vector<double> m6 = weak_directions_deg(6.0, "pa_pdlammps");
  EXPECT_TRUE(std::any_of(m6.begin(), m6.end(), [](double a) { return std::abs(a - 30.964) < 1e-3; }));
}

// The bulk bond stiffness of a lattice against the continuum's. 1D with exact cell overlaps:
// the constant kernel's midpoint sum of |xi| is exact (1); the triangular one's is
// sum_k (1 - k/m) k = (m^2 - 1)/6 at integer m, i.e. 1 - 1/m^2. In 2D the model's own nodes
// give the same sum: a bulk node's family of a built grid (PA-PDLAMMPS, m = 3: 0.869, the
// 13% soft bond stiffness that m = 3 grids are known for).
TEST(Quadrature, LatticeBondMomentMatchesClosedFormsAndABuiltFamily) {
  for (double m : {2.0, 3.0, 5.0, 8.0}) {
    EXPECT_NEAR(lattice_bond_moment(Quadrature::Subcell, 1, InfluenceShape::Constant, m), 1.0, 1e-12);
    EXPECT_NEAR(lattice_bond_moment(Quadrature::Subcell, 1, InfluenceShape::Triangular, m),
                1.0 - 1.0 / (m * m), 1e-12);
  }
  for (const char* rule : {"pa_pdlammps", "ipa_hybrid"}) {
    const Model m = build_model(DeckBuilder()
                                    .set("model.dimension", 2)
                                    .set("model.plane", "stress")
                                    .set("material.youngs_modulus", 1.0)
                                    .set("material.density", 1.0)
                                    .set("discretization.spacing", 1.0)
                                    .set("discretization.horizon", 3.0)
                                    .set("discretization.quadrature", rule)
                                    .set("discretization.body.box.min", {0.0, 0.0})
                                    .set("discretization.body.box.max", {15.0, 15.0})
                                    .set("damage.enabled", false)
                                    .set("solver.end_time", 1.0)
                                    .set("solver.time_step", 0.1)
                                    .build("lattice"));
    const NodeSet& ns = m.nodes;
    std::size_t c = 0;  // the node nearest the centre
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (std::hypot(ns.x[0][i] - 7.5, ns.x[1][i] - 7.5) < std::hypot(ns.x[0][c] - 7.5, ns.x[1][c] - 7.5)) c = i;
    double sum = 0;
    for (std::uint64_t b = m.bonds.begin(c); b < m.bonds.end(c); ++b)
      sum += m.bonds.beta[b] / std::abs(m.bonds.inv_length[b]) * ns.volume[m.bonds.neighbor[b]];
    const double continuum = 2 * 3.14159265358979323846 * 27.0 / 3.0;
    const Quadrature q = std::string(rule) == "ipa_hybrid" ? Quadrature::IpaHybrid : Quadrature::PaPdlammps;
    EXPECT_NEAR(lattice_bond_moment(q, 2, InfluenceShape::Constant, 3.0), sum / continuum, 1e-6) << rule;
  }
  EXPECT_NEAR(lattice_bond_moment(Quadrature::PaPdlammps, 2, InfluenceShape::Constant, 3.0), 0.86905, 5e-6);
}
