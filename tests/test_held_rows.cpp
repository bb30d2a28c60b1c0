// Held bond rows (parallel/held_rows.hpp): a rank's kept rows are the whole model's rows, entry
// for entry, under the bond names the ranks exchange; a name in a row it does not hold names no
// bond of its own; the owners' rows reassemble the whole arrays a serial run holds.
#include <gtest/gtest.h>

#include "input/deck_builder.hpp"
#include "parallel/held_rows.hpp"
#include "setup/build_model.hpp"

using namespace periadapt;

namespace {
// A pre-cracked 12 x 9 plate (delta = 3 dx), so that rows differ in length and in broken bonds.
Model plate() {
  return build_model(DeckBuilder()
                         .set("model.dimension", 2)
                         .set("material.youngs_modulus", 1.0)
                         .set("material.density", 1.0)
                         .set("material.critical_stretch", 0.01)
                         .set("discretization.spacing", 1.0)
                         .set("discretization.horizon_factor", 3.0)
                         .set("discretization.body.box.min", std::vector<double>{0.0, 0.0})
                         .set("discretization.body.box.max", std::vector<double>{12.0, 9.0})
                         .append("cracks", DeckBuilder().set("segment", std::vector<std::vector<double>>{
                                                                            {0, 4.5}, {6, 4.5}}))
                         .set("solver.steps", 1)
                         .build("held rows plate"));
}
}  // namespace

TEST(HeldRows, KeptRowsAreTheWholeRowsUnderTheBondNames) {
  Model m = plate();
  const BondFamilies whole = m.bonds;
  ASSERT_TRUE(can_hold_rows(whole));
  std::vector<std::uint32_t> keep;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
    if (i % 3 != 1) keep.push_back(i);
  RowPartition p;
  hold_bond_rows(p, m.bonds, keep);
  const BondFamilies& h = m.bonds;
  EXPECT_TRUE(p.rows_held);
  EXPECT_EQ(whole_bond_count(p, h), whole.num_bonds());
  std::uint64_t kept = 0;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i) {
    const bool held = i % 3 != 1;
    ASSERT_EQ(h.end(i) - h.begin(i), held ? whole.end(i) - whole.begin(i) : 0u) << "row " << i;
    for (std::uint64_t g = whole.begin(i); g < whole.end(i); ++g) {
      std::uint64_t k = 0;
      ASSERT_EQ(h.named(whole.name(i, g), k), held) << "whole bond " << g;
      if (!held) continue;
      EXPECT_EQ(h.name(i, k), whole.name(i, g));
      EXPECT_EQ(h.neighbor[k], whole.neighbor[g]);
      EXPECT_EQ(h.inv_length[k], whole.inv_length[g]);
      EXPECT_EQ(h.beta[k], whole.beta[g]);
      ++kept;
    }
  }
  EXPECT_EQ(kept, h.num_bonds());
  EXPECT_LT(h.num_bonds(), whole.num_bonds());
}

TEST(HeldRows, OwnersRowsReassembleTheWholeArrays) {
  Model m = plate();
  const BondFamilies whole = m.bonds;
  // One rank owning every row: the gather is its own rows, put back in the whole model's places.
  RowPartition p;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i) p.owned.push_back(i);
  p.all_owned = p.owned;
  hold_bond_rows(p, m.bonds, p.owned);
  const BondFamilies back = gather_whole_bonds(p, m.bonds);
  EXPECT_EQ(back.offsets, whole.offsets);
  EXPECT_EQ(back.num_bonds(), whole.num_bonds());
  EXPECT_EQ(back.neighbor, whole.neighbor);
  EXPECT_EQ(back.inv_length, whole.inv_length);
  EXPECT_EQ(back.beta, whole.beta);
  EXPECT_EQ(back.neighbor.capacity(), whole.neighbor.capacity());
}
