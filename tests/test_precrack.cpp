// Pre-crack cutting removes exactly the hand-counted bonds.
#include <gtest/gtest.h>

#include "input/deck_builder.hpp"
#include "input/deck_error.hpp"
#include "setup/build_model.hpp"

using namespace periadapt;

namespace {
// A block of cells of 1 m, `side` cells a side.
DeckBuilder grid(int dim, double side) {
  return DeckBuilder()
      .set("model.dimension", dim)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("material.critical_stretch", 0.01)
      .set("discretization.spacing", 1.0)
      .set("discretization.horizon_factor", 1.5)
      .set("discretization.quadrature", "full")
      .set("discretization.body.box.min", std::vector<double>(dim, 0.0))
      .set("discretization.body.box.max", std::vector<double>(dim, side))
      .set("solver.steps", 1);
}
// 4 x 4 cells of 1 m, nodes at cell centres, delta = 1.5 m (axial and diagonal neighbours).
Deck grid2d(const std::vector<std::vector<double>>& crack) {
  return grid(2, 4.0).append("cracks", DeckBuilder().set("segment", crack)).build("4 x 4 grid");
}
}  // namespace

TEST(PreCrack, FullWidthCutRemovesTenPairs) {
  // Between rows y = 1.5 and y = 2.5: 4 vertical + 6 diagonal bonds = 10 pairs, 20 entries.
  Model m = build_model(grid2d({{0, 2}, {4, 2}}));
  EXPECT_EQ(m.nodes.size(), 16u);
  EXPECT_EQ(m.precrack_bonds, 20u);
}

TEST(PreCrack, PartialCutRemovesFourPairs) {
  // Crack from x = 0 to 1.9: vertical bonds at x = 0.5, 1.5 and the two diagonals crossing
  // y = 2 at x = 1; the diagonals crossing at x = 2 are beyond the crack end.
  Model m = build_model(grid2d({{0, 2}, {1.9, 2}}));
  EXPECT_EQ(m.precrack_bonds, 8u);
}

TEST(PreCrack, CrackEndTouchingABondCutsIt) {
  // Ending exactly at x = 2 adds the two diagonals that cross y = 2 at x = 2.
  Model m = build_model(grid2d({{0, 2}, {2, 2}}));
  EXPECT_EQ(m.precrack_bonds, 12u);
}

TEST(PreCrack, QuadCutsTwelvePairsIn3D) {
  // 2 x 2 x 2 cells, delta = 1.5: across z = 1, 4 vertical bonds and 8 face diagonals.
  const std::vector<std::vector<double>> quad = {{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
  Model m = build_model(
      grid(3, 2.0).append("cracks", DeckBuilder().set("quad", quad)).build("2 x 2 x 2 grid"));
  EXPECT_EQ(m.nodes.size(), 8u);
  EXPECT_EQ(m.precrack_bonds, 24u);
}

TEST(PreCrack, InitialDamageCountsCutBonds) {
  Model m = build_model(grid2d({{0, 2}, {4, 2}}));
  // Corner node (0.5, 1.5): family = 2 axial in-plane + up + down + 3 diagonals... here we only
  // check that nodes next to the cut are damaged and nodes two rows away are not.
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const double y = m.nodes.x[1][i];
    if (y == 1.5 || y == 2.5) EXPECT_GT(m.nodes.damage(i), 0.2);
    else EXPECT_EQ(m.nodes.damage(i), 0.0);
  }
}

// A node on the crack would keep its bonds to both faces (the strict crossing rule) and bridge
// it: such a deck is refused, for the nodes of the grid and for the children refinement by
// method B can put there (sub-cell centres of every level up to max_level).
TEST(PreCrack, ACrackThroughNodesOfAnyReachableLevelIsRefused) {
  auto refused = [](const std::vector<std::vector<double>>& crack, int max_level) {
    DeckBuilder d = grid(2, 4.0).append("cracks", DeckBuilder().set("segment", crack));
    if (max_level > 0) d.set("adapt.max_level", max_level).set("adapt.stretch_trigger", 0.5);
    try {
      build_model(d.build("4 x 4 grid"));
    } catch (const DeckError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto refused_a = [](const std::vector<std::vector<double>>& crack, int max_level) {
    try {
      build_model(grid(2, 4.0)
                      .append("cracks", DeckBuilder().set("segment", crack))
                      .set("adapt.max_level", max_level)
                      .set("adapt.method", "A")
                      .set("adapt.energy_trigger", 0.5)
                      .build("4 x 4 grid, method A"));
    } catch (const DeckError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // Through the node row y = 1.5: its four nodes.
  EXPECT_NE(refused({{0, 1.5}, {4, 1.5}}, 0).find("passes through 4 nodes"), std::string::npos);
  // Ending on the node (0.5, 1.5) only touches it: strictly inside the crack is what bridges
  // (this one is refused for cutting no bond instead).
  EXPECT_EQ(refused({{-1, 1.5}, {0.5, 1.5}}, 0).find("passes through"), std::string::npos);
  // y = 1.25: no node, but the level-1 children of the row y = 1.5 (at 1.25 and 1.75), 8 of them.
  EXPECT_EQ(refused({{0, 1.25}, {4, 1.25}}, 0), "");
  EXPECT_NE(refused({{0, 1.25}, {4, 1.25}}, 1).find("8 nodes of refinement level 1"), std::string::npos);
  // y = 1.125 is a level-2 row, never one of level 1; a cell edge (y = 2) is no level's.
  EXPECT_EQ(refused({{0, 1.125}, {4, 1.125}}, 1), "");
  EXPECT_NE(refused({{0, 1.125}, {4, 1.125}}, 2).find("of refinement level 2"), std::string::npos);
  EXPECT_EQ(refused({{0, 2}, {4, 2}}, 4), "");
  // Method A puts its level-1 nodes on the lattice of half the spacing through the nodes, cell
  // edges included: the edge y = 2 holds 7 of them strictly inside the crack (x = 0.5 ... 3.5,
  // each shared by the cells on either side and counted once).
  const std::string edge_a = refused_a({{0, 2}, {4, 2}}, 1);
  EXPECT_NE(edge_a.find("7 nodes of refinement level 1"), std::string::npos) << edge_a;
  EXPECT_NE(edge_a.find("0.25 m from a node row"), std::string::npos) << edge_a;
  EXPECT_EQ(refused_a({{0, 1.75}, {4, 1.75}}, 1), "");
  EXPECT_NE(refused_a({{0, 1.75}, {4, 1.75}}, 2).find("of refinement level 2"), std::string::npos);
  EXPECT_EQ(refused_a({{0, 1.625}, {4, 1.625}}, 2), "");
  // 3D: the plane z = 0.5 holds the bottom layer of a 2 x 2 x 2 block.
  const std::vector<std::vector<double>> quad = {{0, 0, 0.5}, {2, 0, 0.5}, {2, 2, 0.5}, {0, 2, 0.5}};
  try {
    build_model(grid(3, 2.0).append("cracks", DeckBuilder().set("quad", quad)).build("2 x 2 x 2 grid"));
    ADD_FAILURE() << "a quad through 4 nodes was accepted";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("passes through 4 nodes"), std::string::npos) << e.what();
  }
}

// A bond through a crack's end point (cell diagonals meeting at a cell corner) touches it: cut,
// in both directions and on mirror images alike. In coordinates that are not binary fractions
// the touch's orientation is round-off; decided exactly, one direction of such a pair was cut and
// the other kept (Kalthoff-Winkler's 2 mm grid: 4 entries), a pair pulling one end only.
TEST(PreCrack, ABondThroughACrackEndIsCutBothWaysAndOnMirrorImages) {
  const Vec3 a{0.0, 0.074, 0.0}, b{0.05, 0.074, 0.0};
  const Vec3 a2{0.0, 0.126, 0.0}, b2{0.05, 0.126, 0.0};  // its mirror image about y = 0.1
  int checked = 0;
  for (int di = 1; di <= 3; ++di)
    for (int dj = 1; dj <= 3; ++dj) {
      const Vec3 p{0.05 - 0.001 * di, 0.074 - 0.001 * dj, 0}, q{0.05 + 0.001 * di, 0.074 + 0.001 * dj, 0};
      const Vec3 pm{p[0], 0.2 - p[1], 0}, qm{q[0], 0.2 - q[1], 0};
      EXPECT_TRUE(bond_crosses_segment(p, q, a, b)) << di << " " << dj;
      EXPECT_TRUE(bond_crosses_segment(q, p, a, b)) << di << " " << dj;
      EXPECT_TRUE(bond_crosses_segment(pm, qm, a2, b2)) << di << " " << dj;
      EXPECT_TRUE(bond_crosses_segment(qm, pm, a2, b2)) << di << " " << dj;
      ++checked;
    }
  EXPECT_EQ(checked, 9);
  // The whole grid: every cut bond is cut from both ends.
  Model m = build_model(grid(2, 0.0)
                            .set("discretization.spacing", 0.002)
                            .set("discretization.horizon_factor", 3.0)
                            .set("discretization.quadrature", "pa_pdlammps")
                            .set("discretization.body.box.max", std::vector<double>{0.1, 0.2})
                            .append("cracks", DeckBuilder().set("segment", std::vector<std::vector<double>>{
                                                                               {0.0, 0.074}, {0.05, 0.074}}))
                            .build("Kalthoff grid"));
  std::size_t cut = 0, one_sided = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
      if (BondFamilies::intact(m.bonds.beta[k])) continue;
      ++cut;
      const std::uint32_t j = m.bonds.neighbor[k];
      bool back = false;
      for (std::uint64_t r = m.bonds.begin(j); r < m.bonds.end(j); ++r)
        if (m.bonds.neighbor[r] == i) back = !BondFamilies::intact(m.bonds.beta[r]);
      one_sided += !back;
    }
  EXPECT_GT(cut, 0u);
  EXPECT_EQ(one_sided, 0u);
}
