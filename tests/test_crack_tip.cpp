// Crack-tip tracking on a hand-made row of cracked nodes: the tip is the farthest cracked node
// ahead of the origin; the crack "starts" (first_advance_time) as soon as a cracked node lies past
// the pre-crack end, and counts as initiated once it is `advance` ahead.
#include <gtest/gtest.h>

#include "analysis/crack_tip.hpp"

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
