#pragma once
// Crack-tip tracking (Ha & Bobaru; thesis 6.1): the tip is the damaged node (damage above a
// threshold, default 0.35) farthest ahead along the crack direction; tip speed by Eq. 6.1 over
// fixed time windows. Also detects branching: a cross-section of the damaged zone, normal to the
// crack direction, that splits into two bands separated by more than a gap, traced back to the
// fork.
#include <array>
#include <optional>
#include <vector>

#include "core/geometry.hpp"
#include "core/node_set.hpp"

namespace periadapt {

class ArchiveWriter;
class ArchiveReader;

struct CrackTipOptions {
  double threshold = 0.35;
  Vec3 origin{0, 0, 0};      // initial tip (pre-crack end)
  Vec3 direction{1, 0, 0};   // expected propagation direction (unit)
  enum class Side { Both, Upper, Lower } side = Side::Both;  // restrict to one side (2D)
  double window = 2e-6;      // speed window (s)
  double advance = 0.0;      // tip must move this far ahead of the origin to count as started
  double branch_gap = 0.0;   // bands farther apart than this count as two branches
  double column = 0.0;       // width of the cross-sections used for branch detection
  double link = 0.0;         // damaged nodes closer than this belong to the same crack (0: all)
  double seed_radius = 0.0;  // damaged nodes this close to the origin start the crack
};

struct TipSample {
  double time;
  Vec3 position;
  double advance;  // projection on the direction, from the origin
};

class CrackTipTracker {
 public:
  explicit CrackTipTracker(const CrackTipOptions& opt) : opt_(opt) {}

  // Records the tip at time t; returns the sample (nullopt when no node is damaged enough).
  std::optional<TipSample> observe(const NodeSet& nodes, double t);

  // Windowed speed at the most recent sample (Eq. 6.1), 0 before the first full window.
  double current_speed() const { return current_speed_; }
  std::optional<double> initiation_time() const { return initiation_; }
  // First time the tip lies ahead of the origin at all (the thesis' "crack starts propagating":
  // a node past the pre-crack end is cracked); initiation_time() asks for `advance` more.
  std::optional<double> first_advance_time() const { return first_advance_; }
  // Branching: the fork (where the crack splits into two bands) and the time its tip passed it;
  // detected once two bands lie more than branch_gap apart, which is the separation point/time.
  std::optional<double> branching_time() const { return branching_time_; }
  std::optional<Vec3> branching_point() const { return branching_point_; }
  std::optional<double> separation_time() const { return separation_time_; }
  std::optional<Vec3> separation_point() const { return separation_point_; }

  const std::vector<TipSample>& path() const { return samples_; }
  // Window speeds (t_mid, v) over the whole run.
  const std::vector<std::array<double, 2>>& speeds() const { return window_speeds_; }
  // Branch symmetry about the crack line (the line through the origin along the direction): the
  // Hausdorff distance between the crack's cracked nodes ahead of the origin on one side and the
  // mirror images of those on the other side; 0 for a perfectly symmetric pattern, nullopt when
  // one side has none.
  std::optional<double> mirror_asymmetry(const NodeSet& nodes) const;
  double mean_speed() const;   // mean over windows after initiation while the tip moves
  double max_speed() const;
  // Checkpoints: everything observed so far.
  void save_state(ArchiveWriter& w) const;
  void restore_state(ArchiveReader& r);

 private:
  void detect_branching(const NodeSet& nodes, const std::vector<std::uint32_t>& crack, double t);
  std::vector<std::uint32_t> crack_nodes(const NodeSet& nodes) const;
  CrackTipOptions opt_;
  std::vector<TipSample> samples_;
  std::vector<std::array<double, 2>> window_speeds_;
  std::optional<TipSample> window_start_;
  double current_speed_ = 0;
  std::optional<double> initiation_;
  std::optional<double> first_advance_;
  // Advance at the first observation (the initial state): where a pre-crack's own damage band
  // already reaches past the origin (a pre-crack tip in a refined zone) growth counts from there.
  std::optional<double> start_advance_;
  std::optional<double> branching_time_;
  std::optional<Vec3> branching_point_;
  std::optional<double> separation_time_;
  std::optional<Vec3> separation_point_;
  // crack_nodes() of the previous call (ids) and their flags, where the next search starts.
  mutable std::vector<std::uint32_t> last_crack_;
  mutable std::vector<char> linked_;
};

}  // namespace periadapt
