#include "run/crack_tip_observer.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "io/atomic_output.hpp"
#include "analysis/rayleigh_speed.hpp"
#include "io/line_plot.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {
namespace {
CrackTipOptions tip_options(const Deck& dk, const Model& m) {
  CrackTipOptions tip;
  tip.threshold = dk.output.tip_threshold;
  if (!dk.cracks.empty()) {
    const Vec3 a = dk.cracks[0].points[0], b = dk.cracks[0].points[1];
    tip.origin = b;
    tip.direction = scale(sub(b, a), 1.0 / norm(sub(b, a)));
  }
  if (dk.output.tip_origin) tip.origin = *dk.output.tip_origin;
  if (dk.output.tip_direction) tip.direction = *dk.output.tip_direction;
  tip.side = dk.output.tip_side == "upper"   ? CrackTipOptions::Side::Upper
             : dk.output.tip_side == "lower" ? CrackTipOptions::Side::Lower
                                             : CrackTipOptions::Side::Both;
  tip.window = dk.output.tip_window;
  tip.advance = dk.output.tip_advance ? *dk.output.tip_advance : m.grid_spacing;
  tip.column = m.grid_spacing;
  tip.branch_gap = dk.output.branch_gap ? *dk.output.branch_gap : m.horizon;
  // Two grid spacings bridge the gaps a crack band has on any level; the pre-crack's own band
  // within a horizon of its tip starts the crack.
  tip.link = 2.0 * m.grid_spacing;
  tip.seed_radius = m.horizon;
  return tip;
}

nlohmann::json time_or_null(const std::optional<double>& t) {
  return t ? nlohmann::json(*t) : nlohmann::json(nullptr);
}
}  // namespace

CrackTipObserver::CrackTipObserver(const RunView& view)
    : tip_(tip_options(view.deck, view.model)), tracker_(tip_) {}

void CrackTipObserver::on_step(RunView& view, long step, bool closing) {
  if (!view.history_due(step, closing)) return;
  if (auto s = tracker_.observe(view.model.nodes, view.vv.time())) last_tip_ = s->position;
}

std::string CrackTipObserver::progress_note() const {
  return tracker_.initiation_time() ? fmt::format("tip v = {:.0f} m/s", tracker_.current_speed())
                                    : std::string();
}

void CrackTipObserver::save(ArchiveWriter& w) {
  w.tag("TIPS");
  tracker_.save_state(w);
  w.put(last_tip_);
}

void CrackTipObserver::restore(ArchiveReader& r, RunView&) {
  r.tag("TIPS");
  tracker_.restore_state(r);
  r.get(last_tip_);
}

void CrackTipObserver::finish(RunView& view, RunResult& res) {
  nlohmann::json& j = res.summary;
  const NodeSet& ns = view.model.nodes;
  nlohmann::json c;
  res.crack = CrackReport{tracker_.first_advance_time(), tracker_.initiation_time(),
                          tracker_.branching_time(), tracker_.mean_speed(), tracker_.max_speed()};
  c["threshold"] = tip_.threshold;
  c["initiation_time_s"] = time_or_null(tracker_.initiation_time());
  c["branching_time_s"] = time_or_null(tracker_.branching_time());
  c["first_advance_time_s"] = time_or_null(tracker_.first_advance_time());
  if (tracker_.branching_point()) {
    c["branch_length_m"] = norm(sub(*tracker_.branching_point(), tip_.origin));
    c["branch_separation_time_s"] = *tracker_.separation_time();
    c["branch_separation_length_m"] = norm(sub(*tracker_.separation_point(), tip_.origin));
    const std::optional<double> asym = tracker_.mirror_asymmetry(ns);
    c["branch_asymmetry_m"] = asym ? nlohmann::json(*asym) : nlohmann::json(nullptr);
  }
  if (!tracker_.path().empty()) {
    // Angle of the segment from the initial tip to the last tip, from the tracking direction
    // (counter-clockwise positive): the path angle of a straight crack.
    const Vec3 r = sub(tracker_.path().back().position, tip_.origin);
    const Vec3 nrm{-tip_.direction[1], tip_.direction[0], 0.0};
    if (norm(r) > tip_.advance)
      c["path_angle_deg"] = std::atan2(dot(r, nrm), dot(r, tip_.direction)) * 180.0 / M_PI;
  }
  c["mean_speed_m_s"] = tracker_.mean_speed();
  c["max_speed_m_s"] = tracker_.max_speed();
  // A tip cannot outrun the Rayleigh wave: a faster tracked tip jumped (a crack nucleated ahead
  // of it, or another branch became the tip), and its speed is the tracker's, not a crack's.
  const MaterialLaw& mat = view.model.material;
  const double cR = rayleigh_speed(ns.dim, mat.plane, mat.E, mat.nu, mat.rho);
  if (cR > 0) {
    c["rayleigh_speed_m_s"] = cR;
    c["max_speed_above_rayleigh"] = tracker_.max_speed() > cR;
  }
  c["speed_window_s"] = tip_.window;
  nlohmann::json path = nlohmann::json::array();
  for (const TipSample& s : tracker_.path())
    path.push_back({s.time, s.position[0], s.position[1], s.position[2]});
  c["tip_path"] = path;  // [t, x, y, z]
  if (!tracker_.path().empty()) {
    const Vec3& last = tracker_.path().back().position;
    c["final_tip_m"] = {last[0], last[1], last[2]};
    if (!view.deck.grid.holes.empty()) {
      // Crack-hole interaction (thesis 6.3): how close the tracked tip came to any hole.
      double closest = std::numeric_limits<double>::infinity();
      for (const TipSample& s : tracker_.path())
        for (const Shape& h : view.deck.grid.holes)
          closest = std::min(closest, h.distance_to_shape(s.position));
      c["closest_approach_to_hole_m"] = closest;
    }
  }
  nlohmann::json sp = nlohmann::json::array();
  for (const auto& w : tracker_.speeds()) sp.push_back({w[0], w[1]});
  c["speed_history"] = sp;  // [t_mid, v]
  j["crack"] = c;
  if (view.write_files && !tracker_.speeds().empty()) {
    // Tip speed over time (Eq. 6.1 windows) as CSV and a plot.
    PlotSeries ps{"tip speed (Eq. 6.1)", {}, {}};
    write_file_atomically(view.dir + "/crack_speed.csv", [&](std::ostream& sc) {
      sc << "time_s,tip_speed_m_s\n";
      for (const auto& w : tracker_.speeds()) {
        sc << fmt::format("{:.9e},{:.6e}\n", w[0], w[1]);
        ps.x.push_back(w[0] * 1e6);
        ps.y.push_back(w[1]);
      }
    });
    PlotOptions po;
    po.title = "crack tip speed";
    po.x_label = "time (us)";
    po.y_label = "speed (m/s)";
    write_line_plot(view.dir + "/crack_speed.png", {ps}, po);
  }
}

}  // namespace periadapt
