#include "analysis/crack_tip.hpp"

#include "core/binary_archive.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/cell_grid.hpp"

namespace periadapt {

namespace {
Vec3 transverse_of(const Vec3& d) { return {-d[1], d[0], 0.0}; }
}  // namespace

std::vector<std::uint32_t> CrackTipTracker::crack_nodes(const NodeSet& ns) const {
  // Damaged nodes, then the ones linked to the initial tip through chains of damaged nodes at
  // most `link` apart: cracks nucleating elsewhere (edges, corners) are not this crack.
  auto damaged = [&](std::size_t i) {
    return (ns.flags[i] & kActive) && ns.damage(i) > opt_.threshold;
  };
  std::vector<std::uint32_t> dmg;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (damaged(i)) dmg.push_back(static_cast<std::uint32_t>(i));
  if (dmg.empty() || !(opt_.link > 0)) return dmg;
  // Between refinement events damage only spreads: if every node of the crack found last time is
  // still active and damaged, that crack is still connected (links depend on reference positions
  // only) and can only have grown, so the search starts from it; else (an event switched some of
  // its nodes off) the crack is found afresh. Same nodes either way.
  linked_.resize(ns.size(), 0);
  bool kept = true;
  for (std::uint32_t i : last_crack_) kept = kept && damaged(i);
  if (!kept) {
    for (std::uint32_t i : last_crack_) linked_[i] = 0;
    last_crack_.clear();
  }
  std::array<std::vector<double>, 3> c;
  for (int d = 0; d < 3; ++d) {
    c[d].resize(dmg.size());
    for (std::size_t k = 0; k < dmg.size(); ++k) c[d][k] = ns.x[d][dmg[k]];
  }
  CellGrid grid(ns.dim, {c[0].data(), c[1].data(), c[2].data()}, dmg.size(), opt_.link);
  std::vector<char> seen(dmg.size(), 0);
  std::vector<std::uint32_t> queue;
  for (std::size_t k = 0; k < dmg.size(); ++k) seen[k] = linked_[dmg[k]];
  grid.for_each_within(opt_.origin, opt_.seed_radius, [&](std::uint32_t k, double) {
    if (!seen[k]) seen[k] = 1, queue.push_back(k);
  });
  // Damaged nodes next to the known crack join it (then their neighbours, below).
  if (!last_crack_.empty())
    for (std::uint32_t k = 0; k < dmg.size(); ++k) {
      if (seen[k]) continue;
      bool near = false;
      grid.for_each_within({c[0][k], c[1][k], c[2][k]}, opt_.link, [&](std::uint32_t l, double) {
        near = near || (seen[l] && linked_[dmg[l]]);
      });
      if (near) seen[k] = 1, queue.push_back(k);
    }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const std::uint32_t k = queue[q];
    grid.for_each_within({c[0][k], c[1][k], c[2][k]}, opt_.link, [&](std::uint32_t l, double) {
      if (!seen[l]) seen[l] = 1, queue.push_back(l);
    });
  }
  std::vector<std::uint32_t> out;
  for (std::size_t k = 0; k < dmg.size(); ++k)
    if (seen[k]) out.push_back(dmg[k]);
  for (std::uint32_t i : out) linked_[i] = 1;
  last_crack_ = out;
  return out;
}

std::optional<TipSample> CrackTipTracker::observe(const NodeSet& ns, double t) {
  const Vec3 dir = opt_.direction;
  const Vec3 nrm = transverse_of(dir);
  double best = -INFINITY, best_tr = 0;
  std::size_t best_i = ns.size();
  const std::vector<std::uint32_t> crack = crack_nodes(ns);
  for (std::uint32_t i : crack) {
    const Vec3 p{ns.x[0][i], ns.x[1][i], ns.x[2][i]};
    const Vec3 r = sub(p, opt_.origin);
    const double tr = dot(r, nrm);
    // Half a cell of slack keeps the row just across a straight crack line on both sides.
    if (opt_.side == CrackTipOptions::Side::Upper && tr < -0.5 * opt_.column) continue;
    if (opt_.side == CrackTipOptions::Side::Lower && tr > 0.5 * opt_.column) continue;
    const double adv = dot(r, dir);
    // Ties (symmetric branches) go to the larger transverse coordinate, deterministically.
    if (adv > best + 1e-12 || (std::abs(adv - best) <= 1e-12 && tr > best_tr)) {
      best = adv;
      best_tr = tr;
      best_i = i;
    }
  }
  // Only the first observation (the initial state) sets where growth counts from.
  const bool first_call = !start_advance_;
  if (first_call) start_advance_ = best_i == ns.size() ? 0.0 : std::max(0.0, best);
  if (best_i == ns.size()) return std::nullopt;
  TipSample s{t, {ns.x[0][best_i], ns.x[1][best_i], ns.x[2][best_i]}, best};
  samples_.push_back(s);
  if (!first_advance_ && s.advance > *start_advance_) first_advance_ = t;
  if (!initiation_ && s.advance > *start_advance_ + opt_.advance) initiation_ = t;
  if (!window_start_) window_start_ = s;
  if (t - window_start_->time >= opt_.window * (1 - 1e-9)) {
    const double v = norm(sub(s.position, window_start_->position)) / (t - window_start_->time);
    window_speeds_.push_back({0.5 * (t + window_start_->time), v});
    current_speed_ = v;
    window_start_ = s;
  }
  if (!branching_time_ && initiation_) detect_branching(ns, crack, t);
  return s;
}

void CrackTipTracker::detect_branching(const NodeSet& ns, const std::vector<std::uint32_t>& crack,
                                       double t) {
  // 3D: bands separated within the x-y plane (plates whose crack front runs through the
  // thickness z, as in the 3D branching study).
  if (ns.dim < 2 || opt_.column <= 0 || opt_.branch_gap <= 0) return;
  const Vec3 dir = opt_.direction;
  const Vec3 nrm = transverse_of(dir);
  // Cross-sections ahead of the initial tip: (transverse coordinate, node spacing) of the crack's
  // nodes.
  std::map<long, std::vector<std::array<double, 2>>> columns;
  for (std::uint32_t i : crack) {
    const Vec3 r = sub({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, opt_.origin);
    const double adv = dot(r, dir);
    if (adv <= 0) continue;
    columns[static_cast<long>(std::floor(adv / opt_.column))].push_back({dot(r, nrm), ns.spacing[i]});
  }
  for (auto& [col, tr] : columns) std::sort(tr.begin(), tr.end());
  // Two bands at least one undamaged node apart: a gap wider than 1.5 local spacings (a band's
  // own nodes are at most one spacing apart across it).
  auto two_bands = [](const std::vector<std::array<double, 2>>& tr) {
    for (std::size_t k = 1; k < tr.size(); ++k)
      if (tr[k][0] - tr[k - 1][0] > 1.5 * std::max(tr[k][1], tr[k - 1][1])) return true;
    return false;
  };
  for (auto at = columns.begin(); at != columns.end(); ++at) {
    const auto& [col, tr] = *at;
    bool apart = false;
    for (std::size_t k = 1; k < tr.size() && !apart; ++k) apart = tr[k][0] - tr[k - 1][0] > opt_.branch_gap;
    if (!apart) continue;
    // Branches a gap apart (robust against holes in one band); the fork lies upstream, where the
    // contiguous run of two-band cross-sections ending here begins. The crack branched when its
    // tip passed the fork.
    separation_time_ = t;
    separation_point_ = add(opt_.origin, scale(dir, (static_cast<double>(col) + 0.5) * opt_.column));
    long first = col;
    for (auto it = at; it != columns.begin();) {
      --it;
      if (it->first != first - 1 || !two_bands(it->second)) break;
      first = it->first;
    }
    const double fork = static_cast<double>(first) * opt_.column;
    branching_point_ = add(opt_.origin, scale(dir, fork));
    branching_time_ = t;
    for (const TipSample& s : samples_)
      if (s.advance >= fork) {
        branching_time_ = s.time;
        break;
      }
    return;
  }
}

std::optional<double> CrackTipTracker::mirror_asymmetry(const NodeSet& ns) const {
  const Vec3 dir = opt_.direction;
  const Vec3 nrm = transverse_of(dir);
  // (advance, transverse, z) of the nodes on each side; the lower side mirrored.
  std::vector<Vec3> up, low;
  for (std::uint32_t i : crack_nodes(ns)) {
    const Vec3 r = sub({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, opt_.origin);
    const double adv = dot(r, dir), tr = dot(r, nrm);
    if (adv <= 0) continue;
    if (tr > 0) up.push_back({adv, tr, r[2]});
    if (tr < 0) low.push_back({adv, -tr, r[2]});
  }
  if (up.empty() || low.empty()) return std::nullopt;
  // Brute force: called once per run, on the crack's nodes only.
  auto directed = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double worst = 0;
    for (const Vec3& p : a) {
      double best = INFINITY;
      for (const Vec3& q : b) best = std::min(best, norm(sub(p, q)));
      worst = std::max(worst, best);
    }
    return worst;
  };
  return std::max(directed(up, low), directed(low, up));
}

double CrackTipTracker::mean_speed() const {
  if (!initiation_) return 0.0;
  // Windows after initiation, up to the last one in which the tip still moved.
  std::size_t last = 0;
  bool any = false;
  for (std::size_t k = 0; k < window_speeds_.size(); ++k)
    if (window_speeds_[k][0] >= *initiation_ && window_speeds_[k][1] > 0) {
      last = k;
      any = true;
    }
  if (!any) return 0.0;
  double sum = 0;
  int cnt = 0;
  for (std::size_t k = 0; k <= last; ++k)
    if (window_speeds_[k][0] >= *initiation_) {
      sum += window_speeds_[k][1];
      ++cnt;
    }
  return cnt ? sum / cnt : 0.0;
}

double CrackTipTracker::max_speed() const {
  double m = 0;
  for (const auto& w : window_speeds_) m = std::max(m, w[1]);
  return m;
}

void CrackTipTracker::save_state(ArchiveWriter& w) const {
  w.tag("TIPS");
  w.put(samples_);
  w.put(window_speeds_);
  w.put(window_start_);
  w.put(current_speed_);
  w.put(initiation_);
  w.put(first_advance_);
  w.put(start_advance_);
  w.put(branching_time_);
  w.put(branching_point_);
  w.put(separation_time_);
  w.put(separation_point_);
  w.put(last_crack_);
  w.put(linked_);
}

void CrackTipTracker::restore_state(ArchiveReader& r) {
  r.tag("TIPS");
  r.get(samples_);
  r.get(window_speeds_);
  r.get(window_start_);
  r.get(current_speed_);
  r.get(initiation_);
  r.get(first_advance_);
  r.get(start_advance_);
  r.get(branching_time_);
  r.get(branching_point_);
  r.get(separation_time_);
  r.get(separation_point_);
  r.get(last_crack_);
  r.get(linked_);
}

}  // namespace periadapt
