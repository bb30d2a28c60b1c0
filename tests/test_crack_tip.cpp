// Crack-tip tracking on a hand-made row of cracked nodes: the tip is the farthest cracked node
// ahead of the origin; the crack "starts" (first_advance_time) as soon as a cracked node lies past
// the pre-crack end, and counts as initiated once it is `advance` ahead.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/rayleigh_speed.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "analysis/crack_tip.hpp"
#include "analysis/refinement_coverage.hpp"

using namespace periadapt;

namespace {
// Nodes on y = 0 at x = 0.5, 1.5, ..., 9.5 (spacing 1), none cracked.
NodeSet row() {
  NodeSet ns;
  ns.dim = 2;
  for (int k = 0; k < 10; ++k) {
    const std::size_t i = ns.append({0.5 + k, 0.0, 0.0}, 1.0, 1.0);
    ns.family_weight[i] = 1.0;
  }
  return ns;
}
void crack_up_to(NodeSet& ns, double x) {
  for (std::size_t i = 0; i < ns.size(); ++i) ns.broken_weight[i] = ns.x[0][i] <= x ? 0.5 : 0.0;
}
}  // namespace

TEST(CrackTip, FirstAdvanceAndInitiationFollowTheTipPastTheOrigin) {
  CrackTipOptions o;
  o.origin = {4.0, 0.0, 0.0};  // pre-crack end between the nodes at 3.5 and 4.5
  o.direction = {1.0, 0.0, 0.0};
  o.advance = 2.0;
  CrackTipTracker tr(o);
  NodeSet ns = row();
  crack_up_to(ns, 3.5);  // the pre-crack's own damaged nodes
  auto s = tr.observe(ns, 1.0);
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->advance, -0.5);
  EXPECT_FALSE(tr.first_advance_time());
  crack_up_to(ns, 4.5);  // half a spacing past the origin: the crack has started
  s = tr.observe(ns, 2.0);
  EXPECT_DOUBLE_EQ(s->advance, 0.5);
  EXPECT_EQ(tr.first_advance_time(), 2.0);
  EXPECT_FALSE(tr.initiation_time());
  crack_up_to(ns, 6.5);  // 2.5 ahead > advance
  s = tr.observe(ns, 3.0);
  EXPECT_DOUBLE_EQ(s->position[0], 6.5);
  EXPECT_EQ(tr.first_advance_time(), 2.0);
  EXPECT_EQ(tr.initiation_time(), 3.0);
}

TEST(CrackTip, GrowthCountsFromThePreCracksOwnBandWhenItReachesPastTheOrigin) {
  // A pre-crack tip inside a refined zone: its own damaged band already reaches half a spacing
  // past the origin in the initial state. The crack starts when the tip moves beyond that.
  CrackTipOptions o;
  o.origin = {4.0, 0.0, 0.0};
  o.direction = {1.0, 0.0, 0.0};
  o.advance = 2.0;
  CrackTipTracker tr(o);
  NodeSet ns = row();
  crack_up_to(ns, 4.5);
  ASSERT_TRUE(tr.observe(ns, 0.0));
  EXPECT_FALSE(tr.first_advance_time());
  ASSERT_TRUE(tr.observe(ns, 1.0));
  EXPECT_FALSE(tr.first_advance_time());
  crack_up_to(ns, 5.5);
  ASSERT_TRUE(tr.observe(ns, 2.0));
  EXPECT_EQ(tr.first_advance_time(), 2.0);
  EXPECT_FALSE(tr.initiation_time());  // 1 past the band's end, less than `advance`
  crack_up_to(ns, 6.5);                 // 2.5 past the origin but only 2 past the band's end
  ASSERT_TRUE(tr.observe(ns, 2.5));
  EXPECT_FALSE(tr.initiation_time());
  crack_up_to(ns, 7.5);                 // 3 past it
  ASSERT_TRUE(tr.observe(ns, 3.0));
  EXPECT_EQ(tr.initiation_time(), 3.0);
}

TEST(CrackTip, MirrorAsymmetryIsTheHausdorffDistanceBetweenTheMirroredBranches) {
  // Two branches leaving the crack line at x = 2: nodes at (2 + k, +-0.5 k), k = 1..4, plus the
  // pre-crack's cracked nodes on the line. Symmetric: 0. Moving the last upper node up by 0.3
  // leaves it 0.3 from its mirror image, the largest gap either way.
  NodeSet ns;
  ns.dim = 2;
  auto add = [&](double x, double y) {
    const std::size_t i = ns.append({x, y, 0.0}, 1.0, 1.0);
    ns.family_weight[i] = 1.0;
    ns.broken_weight[i] = 0.5;
    return i;
  };
  for (double x : {0.5, 1.5}) add(x, 0.0);
  std::size_t last_up = 0;
  for (int k = 1; k <= 4; ++k) {
    last_up = add(2.0 + k, 0.5 * k);
    add(2.0 + k, -0.5 * k);
  }
  CrackTipOptions o;
  o.origin = {1.0, 0.0, 0.0};
  o.direction = {1.0, 0.0, 0.0};
  o.link = 1.7;  // the branch nodes are 1.1 apart, the first 1.6 from the last pre-crack node
  o.seed_radius = 1.0;
  CrackTipTracker tr(o);
  ASSERT_TRUE(tr.mirror_asymmetry(ns));
  EXPECT_NEAR(*tr.mirror_asymmetry(ns), 0.0, 1e-15);
  ns.x[1][last_up] += 0.3;
  EXPECT_NEAR(*tr.mirror_asymmetry(ns), 0.3, 1e-12);
}

namespace {
// Runs a tracker over a crack whose front is at x = 4.5 + t at time t = 0 ... 5 (nodes at or
// behind the front damaged), for the nodes `points` (spacing 1): tip measured along x from the
// origin, columns one spacing wide, branches counted apart beyond a gap of 5.
CrackTipTracker track_fork(const std::vector<std::array<double, 2>>& points) {
  NodeSet ns;
  ns.dim = 2;
  for (const auto& p : points) ns.family_weight[ns.append({p[0], p[1], 0.0}, 1.0, 1.0)] = 1.0;
  CrackTipOptions o;
  o.origin = {0.0, 0.0, 0.0};
  o.direction = {1.0, 0.0, 0.0};
  o.advance = 1.0;
  o.column = 1.0;
  o.branch_gap = 5.0;
  o.link = 1.5;  // branch nodes are 1.41 apart
  o.seed_radius = 1.0;
  CrackTipTracker tr(o);
  for (int t = 0; t <= 5; ++t) {
    for (std::size_t i = 0; i < ns.size(); ++i) ns.broken_weight[i] = ns.x[0][i] <= 4.5 + t ? 0.5 : 0.0;
    tr.observe(ns, t);
  }
  return tr;
}
}  // namespace

TEST(CrackTip, BranchingIsTracedBackToTheForkAndTimedWhenTheTipPassedIt) {
  // A crack along y = 0 (x = 0.5 ... 4.5, spacing 1) that forks into two 45-deg branches, nodes
  // (4.5 + k, +-k), k = 1..4. The branches are more than branch_gap = 5 apart first at x = 7.5
  // (gap 6, t = 3: the separation); cross-sections x = 6.5 and 5.5 still show two bands (gaps 4
  // and 2 > 1.5 spacings), x = 4.5 one: the fork is at the start of the x = 5.5 column, 5.0, and
  // the tip passed it at t = 1.
  std::vector<std::array<double, 2>> points;
  for (int k = 0; k < 5; ++k) points.push_back({0.5 + k, 0.0});
  for (int k = 1; k <= 4; ++k) points.push_back({4.5 + k, 1.0 * k}), points.push_back({4.5 + k, -1.0 * k});
  const CrackTipTracker tr = track_fork(points);
  ASSERT_TRUE(tr.branching_time() && tr.separation_time());
  EXPECT_DOUBLE_EQ(*tr.separation_time(), 3.0);
  EXPECT_DOUBLE_EQ((*tr.separation_point())[0], 7.5);
  EXPECT_DOUBLE_EQ((*tr.branching_point())[0], 5.0);
  EXPECT_DOUBLE_EQ(*tr.branching_time(), 1.0);
}

TEST(CrackTip, AForkIsNotTracedBackIntoATrunkTwoNodesThick) {
  // The forked crack above with a trunk two nodes thick (y = 0 and 1, one spacing apart: one
  // band, its nodes touch). Cross-section x = 4.5 shows gap 1 < 1.5 spacings, one band, so the
  // fork stays at 5.0, passed at t = 1; a rule that split bands at every spacing would trace it
  // back through the trunk to the origin.
  std::vector<std::array<double, 2>> points;
  for (int k = 0; k < 5; ++k) points.push_back({0.5 + k, 0.0}), points.push_back({0.5 + k, 1.0});
  for (int k = 1; k <= 4; ++k) points.push_back({4.5 + k, k + 0.5}), points.push_back({4.5 + k, -k + 0.5});
  const CrackTipTracker tr = track_fork(points);
  ASSERT_TRUE(tr.branching_time() && tr.separation_time());
  EXPECT_DOUBLE_EQ((*tr.branching_point())[0], 5.0);
  EXPECT_DOUBLE_EQ(*tr.branching_time(), 1.0);
}

TEST(CrackTip, TheCrackFoundBeforeIsExtendedOnlyWhileAllOfItStaysDamaged) {
  // The tracker starts each search from the crack it found last time. A damaged island ahead of
  // the tip must stay out until a chain reaches it, join when one does, and drop out again when
  // an event switches off a node of that chain; a fresh tracker must see the same tip each time.
  CrackTipOptions o;
  o.origin = {0.0, 0.0, 0.0};
  o.direction = {1.0, 0.0, 0.0};
  o.link = 1.5;
  o.seed_radius = 1.0;
  CrackTipTracker tr(o);
  NodeSet ns = row();
  auto crack = [&](std::initializer_list<double> xs) {
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (double x : xs)
        if (std::abs(ns.x[0][i] - x) < 1e-12 && ns.x[1][i] == 0.0) ns.broken_weight[i] = 0.5;
  };
  double t = 0;
  auto tip = [&]() {
    t += 1.0;
    const auto s = tr.observe(ns, t);
    const auto fresh = CrackTipTracker(o).observe(ns, t);
    EXPECT_TRUE(s && fresh);
    EXPECT_EQ(s->position, fresh->position) << "t = " << t;
    return s->position[0];
  };
  crack({0.5, 1.5, 2.5, 7.5, 8.5});
  EXPECT_DOUBLE_EQ(tip(), 2.5);  // the island at 7.5-8.5 is not this crack
  crack({3.5, 4.5, 5.5});
  EXPECT_DOUBLE_EQ(tip(), 5.5);
  crack({6.5});
  EXPECT_DOUBLE_EQ(tip(), 8.5);  // linked through 6.5
  // An event replaces the node at 3.5 by a damaged one nearby: the chain holds.
  ns.flags[3] &= static_cast<std::uint8_t>(~kActive);
  const std::size_t q = ns.append({3.5, 0.2, 0.0}, 1.0, 1.0);
  ns.family_weight[q] = 1.0;
  ns.broken_weight[q] = 0.5;
  EXPECT_DOUBLE_EQ(tip(), 8.5);
  // Another switches 6.5 off with no replacement: 5.5 and 7.5 are 2 apart, beyond the link.
  ns.flags[6] &= static_cast<std::uint8_t>(~kActive);
  EXPECT_DOUBLE_EQ(tip(), 5.5);
}

TEST(RefinementCoverage, CountsRefinedNodesAwayFromCracksAndCracksLeftCoarse) {
  // A row x = 0.5 ... 9.5: cracked nodes at 0.5 and 1.5 (the first coarse, the second refined),
  // refined nodes at 2.5 (1 from a crack), 4.5 (3 away) and 8.5 (7 away). Within radius 2 only
  // 4.5 and 8.5 are far; an inactive refined node (a switched-off parent's stand-in) is ignored.
  NodeSet ns = row();
  ns.broken_weight[0] = ns.broken_weight[1] = 0.5;
  for (std::size_t i : {1u, 2u, 4u, 8u}) ns.level[i] = 1;
  ns.level[9] = 1;
  ns.flags[9] = 0;
  const RefinementCoverage c = refinement_coverage(ns, 0.35, 2.0);
  EXPECT_EQ(c.refined, 4u);
  EXPECT_EQ(c.refined_far_from_cracks, 2u);
  EXPECT_EQ(c.cracked, 2u);
  EXPECT_EQ(c.cracked_coarse, 1u);
  // Without cracks every refined node is far from them.
  for (double& w : ns.broken_weight) w = 0;
  const RefinementCoverage none = refinement_coverage(ns, 0.35, 2.0);
  EXPECT_EQ(none.refined_far_from_cracks, 4u);
  EXPECT_EQ(none.cracked, 0u);
}

// The mean tip speed (Eq. 6.1 windows) averages the windows from initiation to the last one in
// which the tip moved: here 1 and 3 (spacing per window), so 2; the window after the tip stopped
// does not count.
TEST(CrackTip, MeanSpeedAveragesTheWindowsFromInitiationToTheLastMovingOne) {
  CrackTipOptions o;
  o.origin = {4.0, 0.0, 0.0};
  o.direction = {1.0, 0.0, 0.0};
  o.advance = 0.5;
  o.window = 1.0;
  CrackTipTracker tr(o);
  NodeSet ns = row();
  const double tips[] = {3.5, 4.5, 5.5, 6.5, 9.5, 9.5};
  for (int k = 0; k < 6; ++k) {
    crack_up_to(ns, tips[k]);
    ASSERT_TRUE(tr.observe(ns, k));
  }
  ASSERT_EQ(tr.initiation_time(), 2.0);
  EXPECT_DOUBLE_EQ(tr.mean_speed(), 2.0);
  EXPECT_DOUBLE_EQ(tr.max_speed(), 3.0);
}

// The Rayleigh speed against its classical values: c_R / c_s = 0.9194 for a Poisson solid
// (nu = 1/4, plane strain or 3D); Viktorov's approximation (0.862 + 1.14 nu) / (1 + nu) within
// 1% for nu in [0.1, 0.4] (0.65% at 0.1, its worst); plane stress read with nu / (1 + nu), its
// equivalent plane-strain ratio.
TEST(CrackTip, RayleighSpeedIsTheRootOfTheRayleighEquation) {
  const double E = 190e9, rho = 8000;
  auto cs = [&](double nu) { return std::sqrt(E / (2 * (1 + nu)) / rho); };
  EXPECT_NEAR(rayleigh_speed(2, PlaneCondition::Strain, E, 0.25, rho) / cs(0.25), 0.91940, 1e-5);
  EXPECT_NEAR(rayleigh_speed(3, PlaneCondition::None, E, 0.25, rho) / cs(0.25), 0.91940, 1e-5);
  for (double nu : {0.1, 0.2, 0.3, 0.4}) {
    const double viktorov = (0.862 + 1.14 * nu) / (1 + nu);
    EXPECT_NEAR(rayleigh_speed(3, PlaneCondition::None, E, nu, rho) / cs(nu), viktorov, 1e-2 * viktorov) << nu;
    const double eq = nu / (1 + nu);  // plane stress with nu: plane strain with nu / (1 + nu)
    EXPECT_NEAR(rayleigh_speed(2, PlaneCondition::Stress, E, nu, rho) / cs(nu),
                rayleigh_speed(2, PlaneCondition::Strain, E, eq, rho) / cs(eq), 1e-9) << nu;
  }
  EXPECT_EQ(rayleigh_speed(1, PlaneCondition::None, E, 0.25, rho), 0.0);
}
