#include "adapt/adaptor.hpp"

#include "parallel/ghost_layer.hpp"
#include "parallel/held_rows.hpp"
#include "parallel/mpi_env.hpp"

#include "core/binary_archive.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iterator>

#include "adapt/coarsen.hpp"
#include "adapt/event_relaxation.hpp"
#include "analysis/energy.hpp"
#include "core/cell_grid.hpp"
#include "adapt/triggers.hpp"
#include "solver/internal_forces.hpp"
#include "solver/stable_time_step.hpp"

namespace periadapt {

Adaptor::Adaptor(Model& m, VelocityVerlet& vv, const AdaptSpec& spec)
    : m_(m), vv_(vv), spec_(spec), check_regions_(std::getenv("PERIADAPT_CHECK_REGIONS") != nullptr) {
  // The energy trigger is the only reader of the multi-rate densities (its check steps).
  vv_.keep_energies_for_checks(spec_.enabled && spec_.energy_fraction ? spec_.check_every : 0);
  // The stretch trigger reads each row's largest stretch from the force passes (plain pairing);
  // the dual pairing measures it in a sweep of its own at each check.
  m_.track_breakable_stretch =
      spec_.enabled && spec_.stretch_fraction && m_.formulation.passes_row_stretch();
  m_.window_surface_correction = true;
}

std::size_t Adaptor::nodes_added() const {
  std::size_t n = 0;
  for (const RefinementEvent& e : events_)
    if (e.trigger != "coarsen") n += e.stats.children;
  return n;
}

std::size_t Adaptor::nodes_removed() const {
  std::size_t n = 0;
  for (const RefinementEvent& e : events_)
    if (e.trigger == "coarsen") n += e.stats.children;
  return n;
}

double Adaptor::total_energy() {
  std::vector<double> W;
  return kinetic_energy(m_.nodes) + strain_energy(m_, W);
}

void Adaptor::restore_energy(double h_before, const std::vector<std::uint32_t>& rows) {
  NodeSet& ns = m_.nodes;
  const double dh = total_energy() - h_before;
  // Scale the velocities of the rebuilt rows about their mass-weighted mean (momentum kept) so
  // that their kinetic energy absorbs the change of the total energy the event made.
  double M = 0, P[3] = {0, 0, 0};
  for (std::uint32_t i : rows) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kBoundary)) continue;
    const double mi = ns.density[i] * ns.volume[i];
    M += mi;
    for (int d = 0; d < ns.dim; ++d) P[d] += mi * ns.v[d][i];
  }
  if (!(M > 0)) return;
  double krel = 0;
  for (std::uint32_t i : rows) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kBoundary)) continue;
    for (int d = 0; d < ns.dim; ++d) {
      const double w = ns.v[d][i] - P[d] / M;
      krel += 0.5 * ns.density[i] * ns.volume[i] * w * w;
    }
  }
  if (!(krel > 0)) return;
  const double lambda = std::sqrt(std::max(0.0, (krel - dh) / krel));
  for (std::uint32_t i : rows) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kBoundary)) continue;
    for (int d = 0; d < ns.dim; ++d) ns.v[d][i] = P[d] / M + lambda * (ns.v[d][i] - P[d] / M);
  }
}

std::vector<std::uint32_t> Adaptor::parents_for(const std::vector<std::uint32_t>& ids,
                                                const std::vector<char>* refinable) const {
  if (ids.empty()) return {};
  std::vector<char> own;
  if (!refinable) {
    own = refinable_nodes(m_, spec_);
    refinable = &own;
  }
  std::vector<std::uint32_t> parents = apply_visibility(m_, ids, *refinable, spec_.visibility_factor);
  if (spec_.refine_loads) {
    if (!m_.partition.rows_held) {
      add_loaded_neighbours(m_, *refinable, parents);
    } else {
      // A loaded node's row is its owner's: each rank looks at its own, and they share the finds.
      std::vector<std::uint32_t> found = parents;
      add_loaded_neighbours(m_, *refinable, found, &m_.partition.mine);
      std::vector<std::uint32_t> added;
      std::set_difference(found.begin(), found.end(), parents.begin(), parents.end(),
                          std::back_inserter(added));
      added = mpi::all_gather(added);
      parents.insert(parents.end(), added.begin(), added.end());
      std::sort(parents.begin(), parents.end());
    }
  }
  return parents;
}

const std::vector<char>& Adaptor::refinable() {
  if (!refinable_valid_) {
    refinable_ = refinable_nodes(m_, spec_);
    refinable_valid_ = true;
  }
  return refinable_;
}

namespace {

// The rows and their neighbours, ascending: `rows` where every rank holds them; else each
// owner lists its own (collective).
std::vector<std::uint32_t> rows_and_neighbours(const Model& m, const std::vector<std::uint32_t>& rows,
                                               bool held_everywhere) {
  const BondFamilies& bf = m.bonds;
  const RowPartition& p = m.partition;
  // Two families' reach repeats each node about a family's size of times: a mark per node keeps
  // the list (and what the ranks exchange) to distinct ids.
  std::vector<char> seen(m.nodes.size(), 0);
  std::vector<std::uint32_t> out;
  auto add = [&](std::uint32_t j) {
    if (!seen[j]) {
      seen[j] = 1;
      out.push_back(j);
    }
  };
  for (std::uint32_t i : rows) {
    if (!held_everywhere && !(i < p.mine.size() && p.mine[i])) continue;
    add(i);
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) add(bf.neighbor[k]);
  }
  if (!held_everywhere) {
    std::vector<std::uint32_t> all = mpi::all_gather(out);
    for (std::uint32_t j : out) seen[j] = 0;
    out.clear();
    for (std::uint32_t j : all) add(j);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

bool Adaptor::window_sync() const {
  // What an event reads of the kinematic state (docs/distributed.md, "Refinement events"): the
  // parents' families and their members' families, sums taken exactly over each rank's own
  // nodes, and for the refresh the rebuilt rows' new families (LPS: and their members' families,
  // whose dilatations the refresh reads; in the dual pairing a membership new to a rank's
  // region belongs to a rebuilt row too). The options that read the whole model's energy or
  // state sync everything.
  return m_.partition.rows_held && vv_.owned_integration() &&
         spec_.method == NodeGeneration::B && !spec_.conserve_energy && spec_.relax_sweeps == 0 &&
         !spec_.coarsen;
}

void Adaptor::refine(const std::vector<std::uint32_t>& parents, std::size_t identified,
                     const char* trigger) {
  if (parents.empty()) return;
  // Each rank keeps its region current between syncs; the event reads the parents' families and
  // their members' (a child across a crack takes a visible neighbour's own gradient): each
  // member's owner sends it, and the owners before a repartition send the rest.
  const bool window = window_sync();
  const std::vector<int> owners_before = window ? m_.partition.owner : std::vector<int>{};
  const long partitions_before = m_.partition.partitions;
  if (window)
    vv_.sync_nodes(rows_and_neighbours(m_, rows_and_neighbours(m_, parents, false), false));
  else
    vv_.sync_state();
  const auto t0 = std::chrono::steady_clock::now();
  RefinementEvent ev;
  ev.step = vv_.step_count();
  ev.time = vv_.time();
  ev.trigger = trigger;
  ev.identified = identified;
  vv_.synchronize_velocities(!window);
  const double h0 = spec_.conserve_energy ? total_energy() : 0.0;
  refinable_valid_ = false;
  const std::size_t first_new = m_.nodes.size();
  ev.stats = refine_nodes(m_, parents, spec_, spec_.refine_loads);
  // The refresh reads the rebuilt rows' new neighbours (every rank holds those rows now); LPS
  // also their neighbours' dilatations. A node the event brings into a rank's region is reached
  // through a rebuilt family, so these layers are all that can be stale there.
  if (window) {
    std::vector<std::uint32_t> reach = rows_and_neighbours(m_, ev.stats.rebuilt, true);
    if (m_.formulation.state_based()) reach = rows_and_neighbours(m_, reach, false);
    vv_.sync_nodes(reach);
  }
  // Once bonds break, the short waves near a running tip are the crack's own, not the coarse
  // grid's error: relaxing them towards a static balance took the energy a tip runs on.
  const int sweeps = spec_.relax_until_crack && cracked_ ? 0 : spec_.relax_sweeps;
  const std::vector<std::uint32_t> moved = relax_event_rows(m_, ev.stats.rebuilt, first_new, sweeps);
  if (spec_.conserve_energy) restore_energy(h0, ev.stats.rebuilt);
  std::size_t active = 0;
  for (auto f : m_.nodes.flags) active += (f & kActive) != 0;
  ev.active_nodes = active;
  // Every rank holds the rows the event rebuilt until it keeps its own again.
  const StableStep s = stable_time_step(m_, ev.stats.rebuilt);
  if (m_.partition.rows_held)
    rehold_rows(m_.partition, m_.nodes, m_.bonds, m_.quadrature,
                held_reach(m_.formulation.state_based(), m_.formulation.dual_horizon));
  ev.bonds = whole_bond_count(m_.partition, m_.bonds);
  ev.dt_stable = s.dt;
  events_.push_back(ev);
  // Reported once the event is complete (forces refreshed, partition current), so that the
  // run can stop with outputs of a sound state.
  std::string unstable;
  if (vv_.dt() > s.dt * (1 + 1e-9) && !spec_.allow_unstable_step)
    unstable = fmt::format(
        "refinement at step {} (t = {:.4e} s) made the time step unstable: dt = {:.4e} s exceeds "
        "the stable step {:.4e} s of the refined grid (node {}, level {}, x = [{:.6g}, {:.6g}, "
        "{:.6g}]); {}set solver.time_step to {:.3e} s (0.8 of this bound) or less",
        vv_.step_count(), vv_.time(), vv_.dt(), s.dt, s.node,
        static_cast<int>(m_.nodes.level[s.node]), m_.nodes.x[0][s.node], m_.nodes.x[1][s.node],
        m_.nodes.x[2][s.node],
        m_.surface_correction != SurfaceCorrection::None
            ? "the default step estimates the finest level's bound before the run, which the "
              "surface correction's factors on the refined rows can lower: "
            : "",
        0.8 * s.dt);
  if (window) {
    // The partition the refresh's pass would make: a repartition hands rows to ranks whose
    // copies of them and their neighbours are stale, so their previous owners send everything.
    refresh_partition(m_.partition, m_.nodes, m_.bonds);
    ++m_.partition.window_events;
    if (m_.partition.partitions != partitions_before) {
      vv_.sync_state_from(owners_before);
      ++m_.partition.window_events_resynced;
    }
  }
  if (moved.empty()) {
    vv_.refresh(&ev.stats.rebuilt, !window);
  } else {
    std::vector<std::uint32_t> rows = ev.stats.rebuilt;
    rows.insert(rows.end(), moved.begin(), moved.end());
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    vv_.refresh(&rows, !window);
  }
  // The event's cost includes the refresh (forces of the rebuilt rows, their step rates).
  events_.back().stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (window && check_regions_) {
    const long stale = stale_region_nodes(m_.partition, m_.nodes);
    if (stale > 0)
      throw std::logic_error(fmt::format("{} region nodes stale after the refinement event at step {}",
                                         stale, ev.step));
  }
  if (!unstable.empty()) throw UnstableAfterRefinement(unstable);
}

bool Adaptor::coarsen_quiet(const std::vector<double>& E, double alpha) {
  const NodeSet& ns = m_.nodes;
  double emax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && !(ns.flags[i] & kBoundary)) emax = std::max(emax, E[i]);
  // Parents whose children are all quiet and that, back on the grid, would not see a hot node:
  // no hot node within visibility_factor max(delta_parent, delta_hot) of the parent (the
  // refinement rule run backwards), so a refined zone is not coarsened under a passing wave.
  std::vector<char> hot(ns.size(), 0);
  double dhot = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && E[i] >= alpha * emax) hot[i] = 1, dhot = std::max(dhot, ns.horizon[i]);
  std::vector<char> busy(ns.size(), 0);
  for (std::size_t c = 0; c < ns.size(); ++c)
    if (ns.parent[c] >= 0 && (ns.flags[c] & kActive) && hot[c])
      busy[static_cast<std::size_t>(ns.parent[c])] = 1;
  std::vector<std::uint32_t> quiet;
  const std::vector<std::uint32_t> candidates = coarsenable_parents(m_);
  if (candidates.empty()) return false;
  double dpar = 0;
  for (std::uint32_t p : candidates) dpar = std::max(dpar, ns.horizon[p]);
  const double f = spec_.visibility_factor;
  CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, ns.size(),
                f * std::max({dhot, dpar, 1e-300}));
  for (std::uint32_t p : candidates) {
    if (busy[p]) continue;
    bool near = false;
    grid.for_each_within({ns.x[0][p], ns.x[1][p], ns.x[2][p]}, f * std::max(dhot, ns.horizon[p]) * (1 + 1e-12),
                         [&](std::uint32_t j, double d2) {
                           const double r = f * std::max(ns.horizon[j], ns.horizon[p]) * (1 + 1e-12);
                           near = near || (hot[j] && d2 <= r * r);
                         });
    if (!near) quiet.push_back(p);
  }
  if (quiet.empty()) return false;
  RefinementEvent ev;
  ev.step = vv_.step_count();
  ev.time = vv_.time();
  ev.trigger = "coarsen";
  const auto t0 = std::chrono::steady_clock::now();
  ev.identified = quiet.size();
  vv_.synchronize_velocities();
  const double h0 = spec_.conserve_energy ? total_energy() : 0.0;
  refinable_valid_ = false;
  ev.stats = coarsen_nodes(m_, quiet);
  if (spec_.conserve_energy) restore_energy(h0, ev.stats.rebuilt);
  std::size_t active = 0;
  for (auto f : ns.flags) active += (f & kActive) != 0;
  ev.active_nodes = active;
  ev.bonds = m_.bonds.num_bonds();
  ev.dt_stable = stable_time_step(m_, ev.stats.rebuilt).dt;
  events_.push_back(ev);
  vv_.refresh(&events_.back().stats.rebuilt);
  events_.back().stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

bool Adaptor::rows_can_be_held() const {
  // What reads rows beyond an event's window: coarsening's sweeps, relaxed events' and the
  // energy correction's force passes, surface corrections and the interface fit around the
  // window.
  return !spec_.coarsen && spec_.relax_sweeps == 0 && !spec_.conserve_energy &&
         !spec_.interface_fit && !spec_.ghost_correction &&
         m_.surface_correction == SurfaceCorrection::None && !m_.interface_fit;
}

bool Adaptor::step() {
  const bool live = spec_.enabled && vv_.time() + vv_.dt() >= spec_.start_time * (1 - 1e-12);
  if (!live) return vv_.step();
  const NodeSet& ns = m_.nodes;
  // The energy trigger reads W from the force pass of its check step instead of a second loop
  // over the bonds (and only there: the other steps run the plain force kernel). With multi-rate
  // stepping each row's W comes from its own latest pass: a slow row's is at most k - 1 steps
  // old, as are its forces, and the rows idle at the check step need no pass of their own.
  const bool check_step = (vv_.step_count() + 1) % spec_.check_every == 0;
  const bool check = spec_.energy_fraction && check_step;
  // Owned integration: the energy trigger reads each rank's own rows (owned_energy_check), so
  // the step need not share every row's density.
  const bool owned_check = vv_.owned_integration() && !spec_.coarsen;
  vv_.set_owned_energy_checks(owned_check);
  if (check && !vv_.multirate()) vv_.request_energy_at(vv_.step_count() + 1, !owned_check);
  if (spec_.damage_trigger) {
    vv_.set_undo(true);
    // Each pass refines by at most one level, so max_level + 1 passes always suffice.
    for (int pass = 0;; ++pass) {
      if (!vv_.step()) return false;
      const std::vector<char>& refinable = this->refinable();
      const auto damaged = vv_.rows_damaged_by_last_step();
      const auto ids = damage_trigger(m_, damaged, refinable);
      // Damage grew on a node that can still be refined: bonds broke on a coarse level, so the
      // step is undone and redone on the refined grid (thesis Fig. 3.4).
      bool coarse = false;
      for (std::uint32_t i : ids) coarse = coarse || refinable[i];
      if (coarse && pass <= spec_.max_level) {
        const auto parents = parents_for(ids, &refinable);
        if (!parents.empty()) {
          vv_.undo_last_step();
          refine(parents, ids.size(), "damage");
          continue;
        }
      }
      // Damage grew on the finest level only: the step stands; the coarse nodes that would see
      // it are refined ahead of the crack for the next steps.
      // Batched every check_every steps: if the crack reaches a coarse node first, the branch
      // above refines it with the step redone. The stretch trigger finds the coarse nodes a tip
      // loads by their own bonds; by proximity it would also take the unloaded ones beside the
      // crack's faces, a band of a coarse horizon along every crack.
      if (!ids.empty() && !spec_.stretch_fraction && vv_.step_count() % spec_.check_every == 0)
        refine(parents_for(ids, &refinable), ids.size(), "damage");
      cracked_ = cracked_ || !damaged.empty();
      break;
    }
  } else if (!vv_.step()) {
    return false;
  }
  if (spec_.stretch_fraction && check_step) {
    const std::vector<char>& refinable = this->refinable();
    // Owned integration or held rows: each rank examines its own rows (their stretches are its
    // own, their neighbours in its region), and the ranks gather the nodes found, in the serial
    // order.
    std::vector<std::uint32_t> ids;
    if (vv_.owned_integration() || m_.partition.rows_held) {
      ids = mpi::all_gather(stretch_trigger(m_, spec_, *spec_.stretch_fraction, refinable,
                                            &m_.partition.owned));
      std::sort(ids.begin(), ids.end());
    } else {
      ids = stretch_trigger(m_, spec_, *spec_.stretch_fraction, refinable);
    }
    if (cracked_ && spec_.stretch_reach > 0) ids = near_cracks(m_, ids, spec_.stretch_reach);
    refine(parents_for(ids, &refinable), ids.size(), "stretch");
  }
  if (check && owned_check) {
    if (const std::vector<double>* w = vv_.energy_density_of_owned_rows()) {
      const auto ids = owned_energy_check(*w);
      refine(parents_for(ids, &this->refinable()), ids.size(), "energy");
      return true;
    }
  }
  if (check) {
    vv_.sync_state();
    if (const std::vector<double>* w = vv_.energy_density_recent())
      W_ = *w;
    else
      energy_density(m_, W_);
    std::vector<double>& E = W_;
    if (spec_.total_energy)
      for (std::size_t i = 0; i < ns.size(); ++i) {
        double v2 = 0;
        for (int d = 0; d < ns.dim; ++d) v2 += ns.v[d][i] * ns.v[d][i];
        E[i] += 0.5 * ns.density[i] * v2;
      }
    const double alpha = *spec_.energy_fraction;
    const std::vector<char> refinable = this->refinable();
    const auto ids = energy_trigger(m_, E, alpha, refinable);
    // Coarsening changes which nodes are active: then the flags are taken afresh.
    const bool coarsened = spec_.coarsen && coarsen_quiet(E, alpha);
    refine(parents_for(ids, coarsened ? nullptr : &refinable), ids.size(), "energy");
  }
  return true;
}

std::vector<std::uint32_t> Adaptor::owned_energy_check(const std::vector<double>& W) {
  // energy_trigger() over the rows this rank owns, then gathered: the same nodes in the same
  // order, from the same values (a row's density and velocity are its owner's).
  const NodeSet& ns = m_.nodes;
  const std::vector<std::uint32_t>& rows = m_.partition.owned;
  std::vector<double> E(rows.size());
  double wmax = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::uint32_t i = rows[k];
    E[k] = W[i];
    if (spec_.total_energy) {
      double v2 = 0;
      for (int d = 0; d < ns.dim; ++d) v2 += ns.v[d][i] * ns.v[d][i];
      E[k] += 0.5 * ns.density[i] * v2;
    }
    if ((ns.flags[i] & kActive) && !(ns.flags[i] & kBoundary)) wmax = std::max(wmax, E[k]);
  }
  wmax = mpi::max_real(wmax);
  std::vector<std::uint32_t> ids;
  if (wmax > 0) {
    const std::vector<char>& refinable = this->refinable();
    const double alpha = *spec_.energy_fraction;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const std::uint32_t i = rows[k];
      if ((refinable[i] || ((ns.flags[i] & kActive) && ns.level[i] > 0)) && E[k] >= alpha * wmax)
        ids.push_back(i);
    }
  }
  ids = mpi::all_gather(ids);
  std::sort(ids.begin(), ids.end());
  return ids;
}

void Adaptor::save_state(ArchiveWriter& w) const {
  w.tag("ADPT");
  w.put(std::uint64_t{events_.size()});
  for (const RefinementEvent& e : events_) {
    w.put(e.step);
    w.put(e.time);
    w.put(e.trigger);
    w.put(std::uint64_t{e.identified});
    w.put(std::uint64_t{e.stats.parents});
    w.put(std::uint64_t{e.stats.children});
    w.put(std::uint64_t{e.stats.reanchored});
    w.put(e.stats.momentum_before);
    w.put(e.stats.momentum_after);
    w.put(e.stats.kinetic_before);
    w.put(e.stats.kinetic_after);
    w.put(e.stats.momentum_scale);
    w.put(e.stats.seconds);
    w.put(std::uint64_t{e.active_nodes});
    w.put(std::uint64_t{e.bonds});
    w.put(e.dt_stable);
  }
  w.put<std::uint8_t>(cracked_);
}

void Adaptor::restore_state(ArchiveReader& r) {
  r.tag("ADPT");
  const auto n = r.get<std::uint64_t>();
  events_.clear();
  for (std::uint64_t k = 0; k < n; ++k) {
    RefinementEvent e;
    r.get(e.step);
    r.get(e.time);
    r.get(e.trigger);
    e.identified = r.get<std::uint64_t>();
    e.stats.parents = r.get<std::uint64_t>();
    e.stats.children = r.get<std::uint64_t>();
    e.stats.reanchored = r.get<std::uint64_t>();
    r.get(e.stats.momentum_before);
    r.get(e.stats.momentum_after);
    r.get(e.stats.kinetic_before);
    r.get(e.stats.kinetic_after);
    r.get(e.stats.momentum_scale);
    r.get(e.stats.seconds);
    e.active_nodes = r.get<std::uint64_t>();
    e.bonds = r.get<std::uint64_t>();
    r.get(e.dt_stable);
    events_.push_back(std::move(e));
  }
  cracked_ = r.get<std::uint8_t>() != 0;
  refinable_valid_ = false;
}

}  // namespace periadapt
