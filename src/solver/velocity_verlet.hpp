#pragma once
// Explicit Velocity-Verlet integration (thesis Eq. 3.2) with body loads and prescribed motions.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

struct StepArrays;
class ArchiveWriter;
class ArchiveReader;

struct DivergenceError {
  std::size_t node;
  long step;
  double time;
  std::string what;
};

class VelocityVerlet {
 public:
  VelocityVerlet(Model& model, double dt);

  // Computes forces and accelerations at the current state (call once before stepping).
  void initialize();
  // Checkpoints: the whole integrator state between two steps (restore replaces initialize()).
  void save_state(ArchiveWriter& w) const;
  void restore_state(ArchiveReader& r);
  // Advances one step. Returns false and fills `divergence()` if a non-finite or runaway
  // displacement appears; the model then holds the state of the failed step.
  bool step();

  double time() const { return time_; }
  long step_count() const { return step_; }
  double dt() const { return dt_; }
  double external_work() const { return external_work_; }
  // Resultants at the current state (N): the force a prescribed motion's supports exert on the
  // body over its constrained components (exact sums; collective in a distributed run, where each
  // rank adds the reactions of its own nodes), and the force a load applies.
  std::array<double, 3> reaction_force(const PrescribedMotion& pm) const;
  std::array<double, 3> applied_force(const BodyLoad& load) const;
  std::size_t broken_bonds() const { return broken_total_; }
  const DivergenceError& divergence() const { return divergence_; }
  // Number of bond evaluations done so far (for throughput reports).
  double bond_evaluations() const { return bond_evals_; }
  // Distributed runs: the bonds this rank's own rows evaluated since the run (or its restart)
  // began; the ranks' shares show how evenly the partition spreads the work.
  double owned_bond_evaluations() const { return owned_evals_; }

  // Undo support (refinement triggered by damage redoes the step on the refined grid). When on,
  // every step keeps what undo_last_step() needs: the previous kinematic state and the bonds the
  // step broke.
  // Distributed runs: each rank integrates only the nodes its force passes read
  // (parallel/ghost_layer.hpp), where the model allows it (no contact, impactors, damage overlay
  // or ghost-force table, which read nodes beyond them). Returns whether it does. Collective
  // from then on: sync_state(), called by everything that reads the whole model, brings every
  // node up to date, and each step decides together whether it may leave nodes stale.
  bool enable_owned_integration();
  void sync_state();
  // Brings the listed nodes (ascending, the same list on every rank) up to date from their
  // owners, leaving the others as they are (a refinement event's window). Collective.
  void sync_nodes(const std::vector<std::uint32_t>& ids);
  // sync_state() from the owners `owner` gave the nodes (before a repartition handed rows to
  // ranks whose copies are stale); nodes beyond it are current on every rank. Collective.
  void sync_state_from(const std::vector<int>& owner);
  bool owned_integration() const { return m_.partition.ghost_mode; }

  void set_undo(bool on) { undo_enabled_ = on; }
  void undo_last_step();
  // With undo on: the nodes whose damage the last step raised (bonds of their rows broke).
  std::vector<std::uint32_t> rows_damaged_by_last_step() const;
  // Recomputes loads and accelerations at the current state; call after the grid changed.
  // `rows` (optional): the bond rows the change touched; where a node's force depends on its own
  // row only (plain PMB) just these forces are computed again, the others being unchanged.
  // `sync` false: the caller brought what the pass reads up to date (an event's window).
  void refresh(const std::vector<std::uint32_t>* rows = nullptr, bool sync = true);
  // Asks the force passes that reach step `step` (the step itself, a redo of it, a refresh at
  // it) to write every node's strain-energy density on the way: the bond loop then serves both,
  // instead of a second pass over the bonds (history samples, the energy trigger).
  void request_energy_at(long step, bool every_row = true);
  // Multi-rate stepping (subcycling): every node whose own stable step (Silling-Askari bound of
  // its row) allows k dt with the deck's safety factor, k <= max_ratio, advances as one
  // Velocity-Verlet step of k dt spread over k steps (opening kick, k drifts, closing kick); the
  // others take every step. Between their force passes the slow nodes' positions lie on their
  // straight drift (what Verlet's drift gives them anyway), so their fast neighbours see a
  // consistent configuration, and a slow row's forces are summed once per k steps. Nodes with
  // prescribed motions stay on dt. Needs row-local forces (plain PMB). Call before initialize().
  static constexpr int kMaxRateRatio = 4;
  void set_multirate(double safety, int max_ratio = 2);
  bool multirate() const { return multirate_; }
  // Active nodes on a longer step than dt now.
  std::size_t slow_nodes() const;
  // Before an event changes the grid: puts the velocity of now on every node that is inside a
  // cycle of 3 dt or more (it holds the velocity of its cycle's middle), so that new nodes
  // interpolate, and the event's momentum and kinetic energy use, one instant. refresh() gives
  // the nodes that go on with their cycle a half-step velocity again, from their acceleration
  // after the event.
  void synchronize_velocities(bool sync = true);
  // Per node: its step in units of dt (empty without multi-rate stepping).
  const std::vector<std::uint8_t>& rates() const { return rate_; }
  // Multi-rate stepping: every row's density from its own latest force pass (a slow row's is up
  // to k - 1 steps old, as its forces are), with no extra pass over the rows idle this step.
  // Valid at the check steps of keep_energies_for_checks(). Single rate: energy_density_now().
  const std::vector<double>* energy_density_recent() const {
    if (multirate_ && energy_check_every_ > 0 && energy_.size() == m_.nodes.size()) return &energy_;
    return energy_density_now();
  }
  // Multi-rate stepping: energy_density_recent() is read at the steps that are multiples of
  // `every` (0: never). Every row passes once in any max_ratio consecutive steps, so only the
  // passes of the last max_ratio steps before such a step (and refreshes) need to write their
  // rows' densities; the others run the plain force sweep. Default 1: every pass writes them.
  void keep_energies_for_checks(long every) { energy_check_every_ = every; }
  // The energy densities of the current state when a force pass computed them, else nullptr.
  const std::vector<double>* energy_density_now() const {
    return energy_step_ == step_ && !energy_owned_only_ && energy_.size() == m_.nodes.size()
               ? &energy_
               : nullptr;
  }
  // The energy densities of the current state when a force pass computed them, valid for this
  // rank's rows at least (all rows but after a step that advanced the regions alone), else nullptr.
  const std::vector<double>* energy_density_now_of_own_rows() const {
    return energy_step_ == step_ && energy_.size() == m_.nodes.size() ? &energy_ : nullptr;
  }
  // Owned integration: a trigger that reads only this rank's rows (adapt/adaptor.cpp) asks for
  // their densities with every_row = false, and the step may leave the other rows' unshared.
  // energy_density_of_owned_rows() then gives what energy_density_recent() gives, valid for this
  // rank's rows.
  void set_owned_energy_checks(bool on) { owned_energy_checks_ = on; }
  const std::vector<double>* energy_density_of_owned_rows() const {
    if (multirate_ && energy_check_every_ > 0 && energy_.size() == m_.nodes.size()) return &energy_;
    return energy_step_ == step_ && energy_.size() == m_.nodes.size() ? &energy_ : nullptr;
  }

 private:
  void apply_loads(double t);
  bool region_step_allowed();
  // A node this rank leaves stale during the current region step.
  bool outside_region(std::size_t i) const { return ghost_step_ && !m_.partition.in_region[i]; }
  // closing_kick: also the step's closing half-kick (from close_kick_).
  void compute_accelerations(const std::vector<std::uint32_t>* rows = nullptr,
                             bool subcycle = false, bool closing_kick = false);
  // Sorts nodes onto their rates (all nodes, or the rows an event rebuilt).
  void classify_rates(const std::vector<std::uint32_t>* rows);
  // Takes up the longer rates that waited for a step where the node's cycles line up, and makes
  // this step's kick factors and force rows.
  void prepare_rates();
  void rebuild_rate_rows();
  // The active rows whose cycle closes at `step` (due) or does not (idle).
  void gather_rows(long step, bool due, std::vector<std::uint32_t>& out) const;
  // Raw pointers of the per-node arrays the step loops use.
  StepArrays arrays();
  void impose_motions(double t, bool velocities_only);
  double external_power() const;

  Model& m_;
  double dt_;
  double time_ = 0.0;
  long step_ = 0;
  double external_work_ = 0.0;
  double last_power_ = 0.0;
  std::size_t broken_total_ = 0;
  double bond_evals_ = 0.0;
  double owned_evals_ = 0.0;
  double owned_bonds_of_pass(const std::vector<std::uint32_t>* rows);
  double runaway_limit_ = 0.0;
  DivergenceError divergence_{};
  bool undo_enabled_ = false;
  // Every node's values from `owner`, or the listed ones' (null: all below owner.size()).
  void sync_from(const std::vector<int>& owner, const std::vector<std::uint32_t>* ids);
  bool stale_ = false;       // owned integration: nodes outside this rank's region lag
  bool ghost_step_ = false;  // this step integrates the region only
  std::vector<std::uint32_t> region_rows_;  // step scratch: a partial pass's rows in the region
  bool multirate_ = false;
  double multirate_safety_ = 0.8;
  int max_ratio_ = 2;
  long energy_check_every_ = 1;
  std::vector<std::uint8_t> rate_;    // per node: its step in units of dt (1: every step)
  std::vector<std::uint8_t> target_;  // per node: the rate it qualifies for
  std::vector<std::uint32_t> pending_;  // nodes waiting to take a longer rate
  std::array<std::vector<std::uint32_t>, kMaxRateRatio + 1> class_rows_;  // active nodes by rate
  std::array<double, kMaxRateRatio + 1> class_bonds_{};  // their bond counts
  // This rank's share of class_bonds_ (all its rows in class 1 without multi-rate stepping), for
  // the partition's owner assignment `class_owned_generation_` (-1: to count afresh).
  std::array<double, kMaxRateRatio + 1> class_owned_bonds_{};
  long class_owned_generation_ = -1;
  double pass_bonds_ = 0.0;                               // bonds of this step's pass_rows_
  std::vector<std::uint32_t> pass_rows_, idle_rows_;  // this step's force rows, and the others
  bool full_pass_ = true;                             // every active row is due this step
  struct Synced {
    std::uint32_t node;
    std::uint8_t rate;
  };
  std::vector<Synced> synced_;  // nodes synchronize_velocities() put on the velocity of now
  bool syncing_ = false;
  std::array<double, kMaxRateRatio + 1> open_kick_{}, close_kick_{};
  bool energy_wanted() const;  // this step's passes compute energies (asked for)
  std::vector<long> energy_requests_;  // steps whose force passes also compute energies
  std::vector<long> owned_energy_requests_;  // ... for this rank's rows only
  bool energy_owned_only_ = false;           // energy_ holds this rank's rows only
  bool owned_energy_checks_ = false;
  std::vector<double> energy_;
  long energy_step_ = -1;               // the step energy_ belongs to (-1: none)
  struct Saved {
    std::array<std::vector<double>, 3> u, v, a;
    std::vector<double> broken_weight, v_prev_fixed, reaction;
    double time = 0, external_work = 0, last_power = 0, bond_evals = 0;
    std::vector<Impactor> impactors;
    long step = 0;
    std::size_t broken_total = 0;
    std::vector<std::uint64_t> broken_log;
    std::vector<double> bond_state;  // history laws: every bond's history at the step start
  } saved_;
  // Constrained degrees of freedom, flattened (node*3 + component), with reaction densities.
  std::vector<std::size_t> fixed_dofs_;
  std::vector<double> reaction_;
  std::vector<double> driven_u_;  // step scratch: displacements of velocity-driven components
  // Body-force densities of the loaded nodes' components (node*3 + d), from the loads at the
  // current time; empty without loads, so load-free models do not carry 24 B/node for them.
  std::array<std::vector<double>, 3> body_;
  std::vector<std::uint32_t> body_nodes_;  // the nodes body_ was last written for
  std::vector<double> v_prev_fixed_;
};

}  // namespace periadapt
