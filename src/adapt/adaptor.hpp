#pragma once
// Drives AGRS during an explicit run: after each step it asks the triggers where to refine,
// widens the set by the visibility criterion, refines, and hands the solver a consistent state
// again. With the damage trigger, a step that damaged a refinable node is undone, the grid is
// refined there and the step is redone (thesis Fig. 3.4), so bonds break on the finest level.
#include <string>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "adapt/refine.hpp"
#include "model/model.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

class ArchiveWriter;
class ArchiveReader;

struct RefinementEvent {
  long step = 0;  // the state refined: a damage event that redoes its step has the step before
  double time = 0;
  std::string trigger;           // "energy", "stretch", "damage" or "coarsen"
  std::size_t identified = 0;    // nodes flagged by the trigger
  RefineStats stats;             // parents refined, children created, momentum, kinetic energy
  std::size_t active_nodes = 0;  // after the event
  std::size_t bonds = 0;
  double dt_stable = 0;          // smallest stable step among the rows the event rebuilt
};

// Raised when refinement makes the run's time step unstable.
class UnstableAfterRefinement : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Adaptor {
 public:
  Adaptor(Model& m, VelocityVerlet& vv, const AdaptSpec& spec);
  // One step of the solver with refinement as the triggers ask; false when the solver diverged.
  bool step();
  const std::vector<RefinementEvent>& events() const { return events_; }
  std::size_t nodes_added() const;
  std::size_t nodes_removed() const;  // children returned to their parents by coarsening
  // Whether a distributed run may hold its ranks' own bond rows (parallel/held_rows.hpp): every
  // row the steps and events read outside an event's window is then a rank's own.
  // Whether an event brings only what it reads up to date (its window) rather than every node.
  bool window_sync() const;
  bool rows_can_be_held() const;
  // Checkpoints: the event log (the triggers keep no state between steps).
  void save_state(ArchiveWriter& w) const;
  void restore_state(ArchiveReader& r);

 private:
  // Parents the identified nodes ask for (visibility applied); empty: nothing to refine.
  // `refinable`: the flags of the current node set when the caller has them already.
  std::vector<std::uint32_t> parents_for(const std::vector<std::uint32_t>& ids,
                                         const std::vector<char>* refinable = nullptr) const;
  // adapt.conserve_energy: total energy, and the velocity rescaling of the rebuilt rows that
  // gives back what an event changed.
  double total_energy();
  void restore_energy(double h_before, const std::vector<std::uint32_t>& rows);
  void refine(const std::vector<std::uint32_t>& parents, std::size_t identified, const char* trigger);
  // Returns whether any parent was restored.
  bool coarsen_quiet(const std::vector<double>& E, double alpha);
  // The energy trigger in a run with owned integration: from this rank's rows, gathered.
  std::vector<std::uint32_t> owned_energy_check(const std::vector<double>& W);
  Model& m_;
  VelocityVerlet& vv_;
  AdaptSpec spec_;
  std::vector<RefinementEvent> events_;
  bool cracked_ = false;  // a step has broken a bond (the stretch trigger's reach applies)
  // refinable_nodes() of the current node set; it changes only with events.
  const std::vector<char>& refinable();
  std::vector<double> W_;
  std::vector<char> refinable_;
  bool refinable_valid_ = false;
  // PERIADAPT_CHECK_REGIONS: every window event checks that no rank's region is stale after it.
  bool check_regions_ = false;
};

}  // namespace periadapt
