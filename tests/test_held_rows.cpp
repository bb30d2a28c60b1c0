// Held bond rows (parallel/held_rows.hpp): a rank's kept rows are the whole model's rows, entry
// for entry, under the bond names the ranks exchange; a name in a row it does not hold names no
// bond of its own; the owners' rows, checkpointed in pieces, restore the whole arrays a serial run
// holds and any other split's held rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include "adapt/refine.hpp"
#include "input/deck_builder.hpp"
#include "model/model_state.hpp"
#include "discretize/families.hpp"
#include "parallel/held_rows.hpp"
#include "setup/build_model.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {
// A W x H plate of unit spacing (delta = 3 dx).
DeckBuilder plate_deck(double W, double H) {
  DeckBuilder b;
  b.set("model.dimension", 2)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("material.critical_stretch", 0.01)
      .set("discretization.spacing", 1.0)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.body.box.min", std::vector<double>{0.0, 0.0})
      .set("discretization.body.box.max", std::vector<double>{W, H})
      .set("solver.steps", 1);
  return b;
}

// A pre-cracked 12 x 9 plate (the crack between node rows), so that rows differ in length and in
// broken bonds.
Model plate() {
  return build_model(plate_deck(12, 9)
                         .append("cracks", DeckBuilder().set("segment", std::vector<std::vector<double>>{
                                                                            {0, 4.0}, {6, 4.0}}))
                         .build("held rows plate"));
}

// A piece's bytes read in order, as from its file.
class StringStream final : public ArchiveStream {
 public:
  explicit StringStream(const std::string& b) : b_(b) {}
  void read(void* to, std::size_t n) override {
    if (n > left()) throw ArchiveError("past the end");
    std::memcpy(to, b_.data() + at_, n);
    at_ += n;
  }
  void skip(std::uint64_t n) override {
    if (n > left()) throw ArchiveError("past the end");
    at_ += n;
  }
  std::size_t left() const { return b_.size() - at_; }

 private:
  const std::string& b_;
  std::size_t at_ = 0;
};
}  // namespace

TEST(HeldRows, KeptRowsAreTheWholeRowsUnderTheBondNames) {
  Model m = plate();
  const BondFamilies whole = m.bonds;
  std::vector<std::uint32_t> keep;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
    if (i % 3 != 1) keep.push_back(i);
  RowPartition p;
  hold_bond_rows(p, m.bonds, keep, m.nodes);
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

// The rows an LPS rank holds around its own: every family member of its rows, twice over, as
// the whole model's families give them (the search marks them without storing a bond).
TEST(HeldRows, RowsGrownByFamiliesAreTheFamiliesMembers) {
  const Model m = plate();
  const BondFamilies& bf = m.bonds;
  const std::size_t n = m.nodes.size();
  std::vector<char> rows(n, 0), expected(n, 0);
  rows[0] = expected[0] = 1;  // a corner: two families reach about 6 spacings
  for (int layer = 0; layer < 2; ++layer) {
    std::vector<char> next(expected);
    for (std::size_t i = 0; i < n; ++i)
      if (expected[i])
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) next[bf.neighbor[k]] = 1;
    expected = std::move(next);
  }
  grow_by_families(m.nodes, m.quadrature, rows, 2);
  EXPECT_EQ(rows, expected);
  std::size_t held = 0;
  for (char c : rows) held += c != 0;
  EXPECT_GT(held, bf.end(0) - bf.begin(0) + 1);  // beyond the corner's own family
  EXPECT_LT(held, n);                            // and not the whole plate
}

// After a refinement event the rows a rank has are current, and their bond lists give the same
// two layers as the search: on a plate refined in two zones (the refined parents inactive, rows
// of two sizes), from rows on both levels and a refined parent, with every row listed and with
// every other one, against no row listed (the search alone).
TEST(HeldRows, ListedRowsGrowAsTheSearchDoes) {
  Model m = build_model(plate_deck(24, 16).build("held rows, refined plate"));
  AdaptSpec spec;
  spec.enabled = true;
  refine_nodes(m, test::active_near(m.nodes, 8, 8, 3, 0), spec);
  refine_nodes(m, test::active_near(m.nodes, 17, 6, 2, 0), spec);
  const std::size_t n = m.nodes.size();
  ASSERT_EQ(m.bonds.num_nodes(), n);
  // A corner, the first refined parent, the first and the last child, and a coarse node at
  // the second zone's edge.
  std::vector<char> seeds(n, 0);
  seeds[0] = seeds[n - 1] = 1;
  std::size_t parent = n, child = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (parent == n && !(m.nodes.flags[i] & kActive)) parent = i;
    if (child == n && m.nodes.level[i] == 1) child = i;
  }
  ASSERT_LT(parent, n);
  ASSERT_LT(child, n);
  seeds[parent] = seeds[child] = 1;
  seeds[test::active_near(m.nodes, 19.5, 6, 0.6, 0).at(0)] = 1;
  std::vector<char> searched(seeds);
  grow_by_families(m.nodes, m.quadrature, searched, 2);
  std::vector<char> every(n, 1), alternate(n, 0);
  for (std::size_t i = 0; i < n; i += 2) alternate[i] = 1;
  for (const std::vector<char>* listed : {&every, &alternate}) {
    std::vector<char> grown(seeds);
    grow_by_families(m.nodes, m.quadrature, grown, 2, &m.bonds, listed);
    EXPECT_EQ(grown, searched);
  }
  std::size_t held = 0;
  for (char c : searched) held += c != 0;
  EXPECT_LT(held, n);  // two layers, not the whole plate
}

// After a refinement event a rank holds its rows again where they lie in its arrays (rebuilt rows
// sit at the end): each kept row keeps its contents under its name, the others are let go, and
// the whole model's row lengths are recorded.
TEST(HeldRows, ReheldRowsKeepTheirContentsWhereverTheyLie) {
  Model m = plate();
  const std::size_t n = m.nodes.size();
  // Rows 10 ... 29 searched again, as an event does: they move to the end of the arrays.
  std::vector<char> moved(n, 0);
  for (std::size_t i = 10; i < 30; ++i) moved[i] = 1;
  m.bonds.neighbor.reserve(2 * m.bonds.neighbor.size());  // room to append, not compact
  rebuild_rows(m.bonds, m.nodes, m.quadrature, moved);
  const BondFamilies whole = m.bonds;
  ASSERT_FALSE(whole.ends.empty());
  RowPartition p;
  p.owner.assign(n, 0);
  p.mine.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) p.mine[i] = i % 3 != 1;
  p.nodes = n;
  p.bonds = m.bonds.neighbor.size();
  p.rows_held = true;
  p.held.assign(n, 1);
  p.whole_offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    p.whole_offsets[i + 1] = p.whole_offsets[i] + whole.end(i) - whole.begin(i);
  const std::vector<std::uint64_t> lengths = p.whole_offsets;
  const BondFamilies& h = m.bonds;
  auto check = [&](const char* when) {
    EXPECT_EQ(p.whole_offsets, lengths) << when;
    std::uint64_t kept = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const bool held = p.mine[i];
      EXPECT_EQ(p.held[i], held) << when;
      ASSERT_EQ(h.end(i) - h.begin(i), held ? whole.end(i) - whole.begin(i) : 0u)
          << when << ", row " << i;
      for (std::uint64_t g = whole.begin(i); held && g < whole.end(i); ++g) {
        std::uint64_t k = 0;
        ASSERT_TRUE(h.named(whole.name(i, g), k)) << when;
        EXPECT_EQ(h.neighbor[k], whole.neighbor[g]) << when;
        EXPECT_EQ(h.inv_length[k], whole.inv_length[g]) << when;
        EXPECT_EQ(h.beta[k], whole.beta[g]) << when;
        ++kept;
      }
    }
    EXPECT_EQ(kept, h.num_bonds()) << when;
    // Slack between the kept rows stays within a quarter of them.
    EXPECT_LE(h.neighbor.size() - kept, kept / 4) << when;
  };
  // A third of the rows let go: compacted.
  rehold_rows(p, m.nodes, m.bonds, m.quadrature, HeldReach::Own);
  check("a third let go");
  EXPECT_EQ(h.neighbor.size(), h.num_bonds());
  // Two more: left as slack where they lie.
  p.mine[41] = p.mine[42] = 0;
  rehold_rows(p, m.nodes, m.bonds, m.quadrature, HeldReach::Own);
  check("two more let go");
  EXPECT_GT(h.neighbor.size(), h.num_bonds());
}

// The dual-horizon pairing's held rows: every family that holds one of a rank's nodes (whose
// memberships its nodes gather), also across a level interface where horizons differ.
TEST(HeldRows, RadiusReachHoldsEveryFamilyThatHoldsARow) {
  const Model m = build_model(plate_deck(20, 12)
                                  .set("adapt.max_level", 1)
                                  .append("adapt.initial_refinement",
                                          DeckBuilder()
                                              .set("region.box.min", std::vector<double>{8.0, 0.0})
                                              .set("region.box.max", std::vector<double>{20.0, 12.0})
                                              .set("level", 1))
                                  .build("refined half"));
  const BondFamilies& bf = m.bonds;
  const std::size_t n = m.nodes.size();
  // The nodes on either side of the level interface, at mid-height.
  std::size_t fine = n, coarse = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(m.nodes.flags[i] & kActive) || std::abs(m.nodes.x[1][i] - 6.0) > 0.6) continue;
    const double x = m.nodes.x[0][i];
    if (m.nodes.level[i] == 1 && (fine == n || x < m.nodes.x[0][fine])) fine = i;
    if (m.nodes.level[i] == 0 && (coarse == n || x > m.nodes.x[0][coarse])) coarse = i;
  }
  ASSERT_LT(fine, n);
  ASSERT_LT(coarse, n);
  ASSERT_LT(m.nodes.x[0][fine] - m.nodes.x[0][coarse], 1.0);
  for (std::size_t own : {fine, coarse}) {
    std::vector<char> rows(n, 0);
    rows[own] = 1;
    grow_held_rows(m.nodes, m.quadrature, rows, HeldReach::Radius);
    std::size_t families = 0;
    for (std::size_t j = 0; j < n; ++j)
      for (std::uint64_t k = bf.begin(j); k < bf.end(j); ++k)
        if (bf.neighbor[k] == own) {
          EXPECT_TRUE(rows[j]) << "the family of " << j << " holds " << own;
          ++families;
        }
    for (std::uint64_t k = bf.begin(own); k < bf.end(own); ++k) EXPECT_TRUE(rows[bf.neighbor[k]]);
    EXPECT_GT(families, 10u);
  }
}

// A checkpoint of held rows keeps each rank's own rows in a piece: the pieces of two "ranks"
// (odd and even rows) restore the whole arrays a serial run holds, bit for bit and with its room,
// and the held rows of another split, reading only the pieces with rows it holds; a piece with
// another piece's rows is refused.
TEST(HeldRows, CheckpointPiecesRestoreWholeAndHeldRows) {
  Model base = plate();
  // Some broken bonds and a history value, so that the pieces carry more than the fresh build.
  base.bonds.enable_state();
  for (std::uint64_t k = 0; k < base.bonds.num_bonds(); k += 7) base.bonds.beta[k] = 0.0f;
  for (std::uint64_t k = 0; k < base.bonds.num_bonds(); k += 5) base.bonds.state[k] = 1e-3 * k;
  const BondFamilies whole = base.bonds;
  const std::size_t n = base.nodes.size();
  auto held = [&](auto pick) {
    Model m = base;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (pick(i)) m.partition.owned.push_back(i);
      m.partition.owner.push_back(static_cast<int>(i % 2));
    }
    hold_bond_rows(m.partition, m.bonds, m.partition.owned, m.nodes);
    return m;
  };
  const Model even = held([](std::uint32_t i) { return i % 2 == 0; });
  const Model odd = held([](std::uint32_t i) { return i % 2 == 1; });
  auto piece = [](const Model& m) {
    std::string bytes;
    write_bond_rows_piece(m, [&](const char* p, std::size_t k) { bytes.append(p, k); });
    return bytes;
  };
  std::map<std::string, std::string> files = {{"checkpoint.rows.9.0-of-2.bin", piece(even)},
                                              {"checkpoint.rows.9.1-of-2.bin", piece(odd)}};
  const BondPieces pieces{{"checkpoint.rows.9.0-of-2.bin", "checkpoint.rows.9.1-of-2.bin"},
                          {11, 12}};
  ArchiveWriter w;
  save_model_state(w, even, &pieces);
  int reads = 0;
  const PieceReader read = [&](const std::string& f, std::uint64_t sum,
                               const std::function<void(ArchiveStream&)>& parse) {
    EXPECT_EQ(sum, f == pieces.files[0] ? 11u : 12u);
    ++reads;
    StringStream s(files.at(f));
    parse(s);
    EXPECT_EQ(s.left(), 0u);
  };

  Model serial = plate();
  serial.bonds.enable_state();
  ArchiveReader r(w.bytes(), "test");
  restore_model_state(r, serial, read);
  EXPECT_TRUE(r.at_end());
  EXPECT_EQ(serial.bonds.offsets, whole.offsets);
  EXPECT_EQ(serial.bonds.num_bonds(), whole.num_bonds());
  EXPECT_EQ(serial.bonds.neighbor, whole.neighbor);
  EXPECT_EQ(serial.bonds.inv_length, whole.inv_length);
  EXPECT_EQ(serial.bonds.beta, whole.beta);
  EXPECT_EQ(serial.bonds.state, whole.state);
  EXPECT_EQ(serial.bonds.neighbor.capacity(), whole.neighbor.capacity());

  // Three "ranks" now: this one holds every third row, from whichever piece has it.
  Model third = plate();
  third.bonds.enable_state();
  std::vector<std::uint32_t> keep;
  for (std::uint32_t i = 0; i < n; i += 3) keep.push_back(i);
  hold_bond_rows(third.partition, third.bonds, keep, third.nodes);
  ArchiveReader r3(w.bytes(), "test");
  restore_model_state(r3, third, read);
  for (std::uint32_t i : keep)
    for (std::uint64_t g = whole.begin(i); g < whole.end(i); ++g) {
      std::uint64_t k = 0;
      ASSERT_TRUE(third.bonds.named(whole.name(i, g), k));
      EXPECT_EQ(third.bonds.beta[k], whole.beta[g]);
      EXPECT_EQ(third.bonds.state[k], whole.state[g]);
      EXPECT_EQ(third.bonds.neighbor[k], whole.neighbor[g]);
    }
  EXPECT_EQ(third.partition.whole_capacity, whole.neighbor.capacity());

  // A rank holding the even rows alone reads their piece alone.
  Model again = plate();
  again.bonds.enable_state();
  hold_bond_rows(again.partition, again.bonds, even.partition.owned, again.nodes);
  reads = 0;
  ArchiveReader r2(w.bytes(), "test");
  restore_model_state(r2, again, read);
  EXPECT_EQ(reads, 1);
  EXPECT_EQ(again.bonds.beta, even.bonds.beta);
  EXPECT_EQ(again.bonds.state, even.bonds.state);

  // A serial run's checkpoint (whole arrays inline) continued with held rows.
  ArchiveWriter ws;
  save_model_state(ws, base);
  Model from_serial = plate();
  from_serial.bonds.enable_state();
  hold_bond_rows(from_serial.partition, from_serial.bonds, keep, from_serial.nodes);
  ArchiveReader rs(ws.bytes(), "test");
  restore_model_state(rs, from_serial);
  EXPECT_EQ(from_serial.bonds.beta, third.bonds.beta);
  EXPECT_EQ(from_serial.bonds.state, third.bonds.state);

  // The same piece twice: its rows twice, the odd rows never.
  const PieceReader twice = [&](const std::string&, std::uint64_t,
                                const std::function<void(ArchiveStream&)>& parse) {
    StringStream s(files.begin()->second);
    parse(s);
  };
  Model bad = plate();
  bad.bonds.enable_state();
  ArchiveReader rb(w.bytes(), "test");
  EXPECT_THROW(restore_model_state(rb, bad, twice), ArchiveError);
}
