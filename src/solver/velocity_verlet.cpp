#include "solver/velocity_verlet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "core/exact_sum.hpp"
#include "parallel/ghost_layer.hpp"
#include "parallel/held_rows.hpp"
#include "parallel/mpi_env.hpp"
#include "parallel/owned_sums.hpp"
#include "solver/internal_forces.hpp"

namespace periadapt {

// The per-node loops of a step, compiled per dimension with their arrays' pointers hoisted (a
// loop over run-time components reloads every vector's data pointer per node and stays scalar).
struct StepArrays {
  const double* x[3];
  double* u[3];
  double* v[3];
  double* a[3];
  const double* f[3];
  const double* body[3];
  double* keep_u[3];  // the state an undo needs, when kept
  double* keep_v[3];
  double* keep_a[3];
  double* cur;
  const double* density;
  const std::uint8_t* rate;  // null: every node on dt
};

namespace {

// Opening half-kick (kick[rate] or half_dt) and drift of the listed nodes (all without a list);
// returns the number of displacement components beyond `lim` or non-finite.
template <int D, bool Keep, bool Multi, bool Listed>
std::size_t kick_drift(const StepArrays& s, const std::uint32_t* rows, std::size_t n,
                       const double* kick, double half_dt, double dt, double lim) {
  const double* x[D];
  double *u[D], *v[D], *ku[D], *kv[D], *ka[D];
  const double* a[D];
  for (int d = 0; d < D; ++d) {
    x[d] = s.x[d], u[d] = s.u[d], v[d] = s.v[d], a[d] = s.a[d];
    ku[d] = s.keep_u[d], kv[d] = s.keep_v[d], ka[d] = s.keep_a[d];
  }
  double* cur = s.cur;
  const std::uint8_t* rate = s.rate;
  std::size_t bad = 0;
#pragma omp parallel for simd schedule(static) reduction(+ : bad)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = Listed ? rows[r] : r;
    const double c = Multi ? kick[rate[i]] : half_dt;
    for (int d = 0; d < D; ++d) {
      if constexpr (Keep) {
        ku[d][i] = u[d][i];
        kv[d][i] = v[d][i];
        ka[d][i] = a[d][i];
      }
      const double vi = v[d][i] + c * a[d][i];
      const double ui = u[d][i] + dt * vi;
      v[d][i] = vi;
      u[d][i] = ui;
      cur[4 * i + d] = x[d][i] + ui;
      bad += !(std::abs(ui) <= lim);
    }
  }
  return bad;
}

// a = (f + b) / rho of the listed rows (all nodes without a list), with the closing half-kick
// (kick[rate] or half_dt) when asked for.
template <int D, bool Loaded, bool Kick, bool Multi>
void accelerate(const StepArrays& s, const std::uint32_t* rows, std::size_t n, const double* kick,
                double half_dt) {
  double *v[D], *a[D];
  const double *f[D], *b[D];
  for (int d = 0; d < D; ++d) v[d] = s.v[d], a[d] = s.a[d], f[d] = s.f[d], b[d] = s.body[d];
  const double* rho = s.density;
  const std::uint8_t* rate = s.rate;
#pragma omp parallel for simd schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = rows ? rows[r] : r;
    const double inv_rho = 1.0 / rho[i];
    const double c = Kick ? (Multi ? kick[rate[i]] : half_dt) : 0.0;
    for (int d = 0; d < D; ++d) {
      const double ai = (f[d][i] + (Loaded ? b[d][i] : 0.0)) * inv_rho;
      a[d][i] = ai;
      if constexpr (Kick) v[d][i] += c * ai;
    }
  }
}

// v += kick a over the listed nodes (all without a list): the closing half-kick of constrained
// models, given after their constrained components' accelerations were zeroed.
template <int D, bool Multi>
void kick_all(const StepArrays& s, const std::uint32_t* rows, std::size_t n, const double* kick,
              double half_dt) {
  double* v[D];
  const double* a[D];
  for (int d = 0; d < D; ++d) v[d] = s.v[d], a[d] = s.a[d];
  const std::uint8_t* rate = s.rate;
#pragma omp parallel for simd schedule(static)
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = rows ? rows[r] : r;
    const double c = Multi ? kick[rate[i]] : half_dt;
    for (int d = 0; d < D; ++d) v[d][i] += c * a[d][i];
  }
}

// Calls f with a compile-time std::bool_constant for the run-time flag b (nest for several).
template <class F>
auto with_bool(bool b, F&& f) {
  return b ? f(std::true_type{}) : f(std::false_type{});
}
template <class F>
auto with_dim(int dim, F&& f) {
  if (dim == 1) return f(std::integral_constant<int, 1>{});
  if (dim == 2) return f(std::integral_constant<int, 2>{});
  return f(std::integral_constant<int, 3>{});
}

}  // namespace

StepArrays VelocityVerlet::arrays() {
  NodeSet& ns = m_.nodes;
  StepArrays s{};
  for (int d = 0; d < 3; ++d) {
    s.x[d] = ns.x[d].data();
    s.u[d] = ns.u[d].data();
    s.v[d] = ns.v[d].data();
    s.a[d] = ns.a[d].data();
    s.f[d] = ns.f[d].data();
    s.body[d] = body_[d].empty() ? nullptr : body_[d].data();
    s.keep_u[d] = saved_.u[d].data();
    s.keep_v[d] = saved_.v[d].data();
    s.keep_a[d] = saved_.a[d].data();
  }
  s.cur = ns.cur.data();
  s.density = ns.density.data();
  s.rate = rate_.empty() ? nullptr : rate_.data();
  return s;
}

VelocityVerlet::VelocityVerlet(Model& model, double dt) : m_(model), dt_(dt) {
  const NodeSet& ns = m_.nodes;
  // A displacement larger than 100 body sizes can only come from an instability.
  double extent = 0;
  for (int d = 0; d < ns.dim; ++d) {
    auto [lo, hi] = std::minmax_element(ns.x[d].begin(), ns.x[d].end());
    if (lo != ns.x[d].end()) extent = std::max(extent, *hi - *lo);
  }
  runaway_limit_ = 100.0 * std::max(extent, m_.grid_spacing);
  for (const PrescribedMotion& pm : m_.motions)
    for (std::uint32_t i : pm.nodes)
      for (int d = 0; d < ns.dim; ++d)
        if (pm.component[d]) fixed_dofs_.push_back(static_cast<std::size_t>(i) * 3 + d);
  std::sort(fixed_dofs_.begin(), fixed_dofs_.end());
  fixed_dofs_.erase(std::unique(fixed_dofs_.begin(), fixed_dofs_.end()), fixed_dofs_.end());
  reaction_.assign(fixed_dofs_.size(), 0.0);
  v_prev_fixed_.assign(fixed_dofs_.size(), 0.0);
}

void VelocityVerlet::apply_loads(double t) {
  const NodeSet& ns = m_.nodes;
  if (m_.loads.empty()) {
    for (auto& b : body_) b.clear();
    return;
  }
  // Only the nodes loaded last time hold a density: clearing those (not every node) keeps this
  // O(loaded) (an event may have changed the lists since).
  if (body_[0].size() == ns.size()) {
    for (std::uint32_t i : body_nodes_)
      for (auto& b : body_) b[i] = 0.0;
  } else {
    for (auto& b : body_) b.assign(ns.size(), 0.0);
  }
  body_nodes_.clear();
  for (const BodyLoad& L : m_.loads) {
    body_nodes_.insert(body_nodes_.end(), L.nodes.begin(), L.nodes.end());
    const double amp = L.amplitude(t);
    for (std::uint32_t i : L.nodes)
      for (int d = 0; d < ns.dim; ++d) body_[d][i] += amp * L.density[d];
  }
}

void VelocityVerlet::impose_motions(double t, bool velocities_only) {
  NodeSet& ns = m_.nodes;
  for (const PrescribedMotion& pm : m_.motions) {
    for (std::uint32_t i : pm.nodes) {
      if (outside_region(i)) continue;
      const double X = ns.x[0][i], Y = ns.x[1][i], Z = ns.x[2][i];
      for (int d = 0; d < ns.dim; ++d) {
        if (!pm.component[d]) continue;
        const Expression& e = *pm.component[d];
        if (pm.kind == PrescribedMotion::Kind::Velocity) {
          ns.v[d][i] = e(X, Y, Z, t);
        } else if (!velocities_only) {
          const double un = e(X, Y, Z, t);
          ns.u[d][i] = un;
          // Velocity consistent with the prescribed path (central difference).
          const double h = 0.5 * dt_;
          ns.v[d][i] = e.depends_on_time() ? (e(X, Y, Z, t + h) - e(X, Y, Z, t - h)) / dt_ : 0.0;
        }
      }
    }
  }
}

void VelocityVerlet::request_energy_at(long step, bool every_row) {
  std::vector<long>& list =
      every_row || !m_.partition.ghost_mode ? energy_requests_ : owned_energy_requests_;
  if (std::find(list.begin(), list.end(), step) == list.end()) list.push_back(step);
}

void VelocityVerlet::set_multirate(double safety, int max_ratio) {
  if (!m_.formulation.row_local())
    throw std::invalid_argument(
        "multi-rate stepping needs forces that depend on a node's own bond row (bond-based PMB "
        "with source-horizon pairing)");
  if (max_ratio < 2 || max_ratio > kMaxRateRatio)
    throw std::invalid_argument("multi-rate stepping: the largest step ratio must be 2 ... " +
                                std::to_string(kMaxRateRatio));
  multirate_ = true;
  multirate_safety_ = safety;
  max_ratio_ = max_ratio;
}

std::size_t VelocityVerlet::slow_nodes() const {
  std::size_t n = 0;
  for (int k = 2; k <= kMaxRateRatio; ++k) n += class_rows_[static_cast<std::size_t>(k)].size();
  return n;
}

void VelocityVerlet::classify_rates(const std::vector<std::uint32_t>* rows) {
  if (!multirate_) return;
  NodeSet& ns = m_.nodes;
  rate_.resize(ns.size(), 1);
  target_.resize(ns.size(), 1);
  // Nodes with prescribed motions take every step: their reactions need their forces each step.
  std::vector<char> driven(ns.size(), 0);
  for (const PrescribedMotion& pm : m_.motions)
    for (std::uint32_t i : pm.nodes) driven[i] = 1;
  auto sort_node = [&](std::size_t i, double k) {
    int t = 1;
    if ((ns.flags[i] & kActive) && !driven[i]) {
      // k = 0: no intact bonds to be unstable in; a lone node can take any step.
      const double bound = k > 0 ? multirate_safety_ * std::sqrt(2.0 * ns.density[i] / k) : INFINITY;
      while (t < max_ratio_ && (t + 1) * dt_ <= bound) ++t;
    }
    target_[i] = static_cast<std::uint8_t>(t);
    const int r = rate_[i];
    if (t < r) {
      // Its step is too long now: back to dt at once. Mid-cycle (p steps since its opening kick
      // of r dt / 2) v is the velocity at r/2 steps in; shifted to now, to first order (unless
      // synchronize_velocities() did so already).
      const long p = step_ % r;
      if (p != 0 && !syncing_)
        for (int d = 0; d < ns.dim; ++d)
          ns.v[d][i] -= (0.5 * r - static_cast<double>(p)) * dt_ * ns.a[d][i];
      rate_[i] = 1;
    }
    // A longer step starts only where the node's old and new cycles both begin (now, or later in
    // prepare_rates): joining a cycle midway would skip part of its opening kick.
    if (t > rate_[i]) {
      if (step_ % t == 0 && step_ % rate_[i] == 0)
        rate_[i] = static_cast<std::uint8_t>(t);
      else
        pending_.push_back(static_cast<std::uint32_t>(i));
    }
  };
  if (rows && m_.partition.rows_held) {
    // Held bond rows: each row's sum from its owner.
    std::vector<double> K(ns.size(), 0.0);
    for (std::uint32_t i : *rows)
      if (m_.partition.mine[i]) K[i] = material_stiffness_row(ns, m_.bonds, material_context(m_), i);
    share_owned_values(m_.partition, K, rows);
    for (std::uint32_t i : *rows) sort_node(i, K[i]);
  } else if (rows) {
    for (std::uint32_t i : *rows)
      sort_node(i, material_stiffness_row(ns, m_.bonds, material_context(m_), i));
  } else {
    std::vector<double> K;
    material_stiffness_sum(ns, m_.bonds, material_context(m_), K);
    // Held bond rows: each row's sum from its owner.
    if (m_.partition.rows_held) share_owned_values(m_.partition, K);
    for (std::size_t i = 0; i < ns.size(); ++i) sort_node(i, K[i]);
  }
  std::sort(pending_.begin(), pending_.end());
  pending_.erase(std::unique(pending_.begin(), pending_.end()), pending_.end());
  rebuild_rate_rows();
}

void VelocityVerlet::rebuild_rate_rows() {
  const NodeSet& ns = m_.nodes;
  for (auto& c : class_rows_) c.clear();
  class_bonds_.fill(0.0);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (ns.flags[i] & kActive) {
      class_rows_[rate_[i]].push_back(static_cast<std::uint32_t>(i));
      class_bonds_[rate_[i]] += static_cast<double>(whole_row_length(m_.partition, m_.bonds, i));
    } else {
      rate_[i] = 1;  // a node that comes back (coarsening) starts on dt
    }
  }
  // The partition weighs each row's bonds by how often it is stepped.
  if (m_.partition.active) m_.partition.rates = rate_;
  class_owned_generation_ = -1;
}

double VelocityVerlet::owned_bonds_of_pass(const std::vector<std::uint32_t>* rows) {
  const RowPartition& p = m_.partition;
  double s = 0;
  if (rows && rows != &pass_rows_) {
    for (std::uint32_t i : *rows)
      if (p.mine[i] && (m_.nodes.flags[i] & kActive))
        s += static_cast<double>(whole_row_length(p, m_.bonds, i));
    return s;
  }
  if (class_owned_generation_ != p.generation) {
    class_owned_bonds_.fill(0.0);
    for (std::uint32_t i : p.owned)
      if (m_.nodes.flags[i] & kActive)
        class_owned_bonds_[multirate_ && i < rate_.size() ? rate_[i] : 1] +=
            static_cast<double>(whole_row_length(p, m_.bonds, i));
    class_owned_generation_ = p.generation;
  }
  // A step's pass takes the classes whose cycles close at this step; a full pass all of them.
  for (int k = 1; k <= kMaxRateRatio; ++k)
    if (!rows || step_ % k == 0) s += class_owned_bonds_[static_cast<std::size_t>(k)];
  return s;
}

void VelocityVerlet::synchronize_velocities(bool sync) {
  if (sync) sync_state();
  if (!multirate_ || syncing_) return;
  syncing_ = true;
  synced_.clear();
  NodeSet& ns = m_.nodes;
  // Rate 2 needs nothing: one step into its cycle, v is already the velocity of now.
  for (int k = 3; k <= kMaxRateRatio; ++k) {
    const long p = step_ % k;
    if (p == 0) continue;
    const double c = (0.5 * k - static_cast<double>(p)) * dt_;
    for (std::uint32_t i : class_rows_[static_cast<std::size_t>(k)]) {
      for (int d = 0; d < ns.dim; ++d) ns.v[d][i] -= c * ns.a[d][i];
      synced_.push_back({i, static_cast<std::uint8_t>(k)});
    }
  }
}

void VelocityVerlet::prepare_rates() {
  if (!multirate_) return;
  if (!pending_.empty()) {
    bool changed = false;
    std::erase_if(pending_, [&](std::uint32_t i) {
      if (i >= rate_.size() || target_[i] <= rate_[i] || !(m_.nodes.flags[i] & kActive)) return true;
      if (step_ % rate_[i] != 0 || step_ % target_[i] != 0) return false;
      rate_[i] = target_[i];
      changed = true;
      return true;
    });
    if (changed) rebuild_rate_rows();
  }
  // A node of rate k opens its k dt step on the steps that start at a multiple of k and closes
  // it (force pass, closing kick) on the steps that end at one.
  const long s0 = step_, s1 = step_ + 1;
  full_pass_ = true;
  for (int k = 1; k <= kMaxRateRatio; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    open_kick_[kk] = s0 % k == 0 ? 0.5 * k * dt_ : 0.0;
    close_kick_[kk] = s1 % k == 0 ? 0.5 * k * dt_ : 0.0;
    if (s1 % k != 0 && !class_rows_[kk].empty()) full_pass_ = false;
  }
  pass_rows_.clear();
  pass_bonds_ = 0.0;
  if (!full_pass_) {
    gather_rows(s1, true, pass_rows_);
    for (int k = 1; k <= kMaxRateRatio; ++k)
      if (s1 % k == 0) pass_bonds_ += class_bonds_[static_cast<std::size_t>(k)];
  }
}

void VelocityVerlet::gather_rows(long step, bool due, std::vector<std::uint32_t>& out) const {
  out.clear();
  for (int k = 1; k <= kMaxRateRatio; ++k)
    if ((step % k == 0) == due) {
      const auto& c = class_rows_[static_cast<std::size_t>(k)];
      out.insert(out.end(), c.begin(), c.end());
    }
}

bool VelocityVerlet::energy_wanted() const {
  return std::find(energy_requests_.begin(), energy_requests_.end(), step_) != energy_requests_.end() ||
         std::find(owned_energy_requests_.begin(), owned_energy_requests_.end(), step_) !=
             owned_energy_requests_.end();
}

void VelocityVerlet::compute_accelerations(const std::vector<std::uint32_t>* rows, bool subcycle,
                                           bool closing_kick) {
  NodeSet& ns = m_.nodes;
  std::erase_if(energy_requests_, [&](long s) { return s < step_; });
  std::erase_if(owned_energy_requests_, [&](long s) { return s < step_; });
  const bool want_energy = energy_wanted();
  // Only the rows' accelerations change in a partial pass (after an undo, the others hold the
  // restored state's, which their forces were not recomputed for); so do only their reactions
  // (below). Its energy field is complete only if the other rows' densities belong to this very
  // state (computed by this step's pass); else the observers make their own.
  // A subcycle pass covers every node with a prescribed motion (they are never slow).
  const bool partial = rows && m_.formulation.refreshes_rows();
  // A subcycle step: the idle rows' densities at this (drifted) state come from their own pass.
  // Densities a region step left for each rank's own rows only do not complete a whole pass's
  // field (an event's refresh may also hand rows to new owners): the observers make their own.
  const bool energy_kept =
      partial && want_energy &&
      (subcycle || (energy_step_ == step_ && (!energy_owned_only_ || ghost_step_)));
  if (subcycle && want_energy) {
    gather_rows(step_, false, idle_rows_);
    // A region step: the sums read each rank's own rows (energy_density_now_of_own_rows()).
    energy_density_rows(m_, energy_, idle_rows_, ghost_step_);
  }
  energy_step_ = want_energy && (!partial || energy_kept) ? step_ : -1;
  energy_owned_only_ = ghost_step_;
  // Multi-rate: a pass also writes its rows' densities (the same sweep), so that each row holds
  // the one of its own latest pass (energy_density_recent()) at the next check step: refreshes
  // always, step passes (those with the closing kick) in the last max_ratio steps before it.
  const long every = energy_check_every_;
  const bool keep_recent =
      multirate_ && every > 0 && (!closing_kick || (every - step_ % every) % every < max_ratio_);
  std::vector<std::uint64_t>* log = undo_enabled_ ? &saved_.broken_log : nullptr;
  m_.partition.ghost_pass = ghost_step_;
  if (partial) {
    broken_total_ += internal_forces_rows(m_, m_.damage_enabled, *rows, log,
                                          energy_kept || keep_recent ? &energy_ : nullptr);
    if (rows == &pass_rows_)
      bond_evals_ += pass_bonds_;  // counted per rate class when the classes were formed
    else
      for (std::uint32_t i : *rows)
        bond_evals_ += static_cast<double>(whole_row_length(m_.partition, m_.bonds, i));
  } else {
    broken_total_ += internal_forces(m_, m_.damage_enabled, log,
                                     want_energy || keep_recent ? &energy_ : nullptr);
    bond_evals_ += static_cast<double>(whole_bond_count(m_.partition, m_.bonds));
  }
  if (m_.partition.active) owned_evals_ += owned_bonds_of_pass(partial ? rows : nullptr);
  m_.partition.ghost_pass = false;
  // Owned integration: only the region's nodes have their forces here.
  const std::vector<std::uint32_t>* accel_rows = partial ? rows : nullptr;
  if (ghost_step_) {
    if (partial) {
      region_rows_.clear();
      for (std::uint32_t i : *rows)
        if (m_.partition.in_region[i]) region_rows_.push_back(i);
      accel_rows = &region_rows_;
    } else {
      accel_rows = &m_.partition.region;
    }
  }
  const std::size_t n = accel_rows ? accel_rows->size() : ns.size();
  const int dim = ns.dim;
  const bool loaded = !body_[0].empty();
  // The step's closing half-kick rides along when no constrained component needs its
  // acceleration zeroed first (the kick of a row left out of a partial pass is zero).
  const bool kick_here = closing_kick && fixed_dofs_.empty();
  const StepArrays sa = arrays();
  const std::uint32_t* row_ids = accel_rows ? accel_rows->data() : nullptr;
  with_dim(dim, [&](auto D) {
    with_bool(loaded, [&](auto L) {
      with_bool(kick_here, [&](auto K) {
        with_bool(sa.rate != nullptr, [&](auto M) {
          accelerate<D(), L(), K(), M()>(sa, row_ids, n, close_kick_.data(), 0.5 * dt_);
        });
      });
    });
  });
  // Constrained components follow their prescribed path: record the reaction density needed.
  // A partial refresh after an event (a subcycle pass lists every driven node) keeps the
  // reactions of the rows it leaves out: their forces were not recomputed (after an undo ns.f
  // even holds the undone step's), and their reactions are the ones recorded, or restored, for
  // this very state. (A full pass here cost K-W a force sweep per event: 18% of its run.)
  std::vector<char> listed;
  if (partial && !subcycle && !fixed_dofs_.empty()) {
    listed.assign(ns.size(), 0);
    for (std::uint32_t i : *rows) listed[i] = 1;
  }
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q) {
    const std::size_t i = fixed_dofs_[q] / 3;
    const int d = static_cast<int>(fixed_dofs_[q] % 3);
    if ((!listed.empty() && !listed[i]) || outside_region(i)) continue;
    const double acc = step_ > 0 ? (ns.v[d][i] - v_prev_fixed_[q]) / dt_ : 0.0;
    reaction_[q] = ns.density[i] * acc - ns.f[d][i] - (loaded ? body_[d][i] : 0.0);
    ns.a[d][i] = 0.0;
  }
  if (closing_kick && !kick_here)
    with_dim(dim, [&](auto D) {
      with_bool(sa.rate != nullptr, [&](auto M) {
        const std::vector<std::uint32_t>* region = ghost_step_ ? &m_.partition.region : nullptr;
        kick_all<D(), M()>(sa, region ? region->data() : nullptr,
                           region ? region->size() : ns.size(), close_kick_.data(), 0.5 * dt_);
      });
    });
}

std::array<double, 3> VelocityVerlet::reaction_force(const PrescribedMotion& pm) const {
  const NodeSet& ns = m_.nodes;
  // Each owner keeps its nodes' reactions (owned integration): exact sums over the ranks' own.
  const RowPartition* part = m_.partition.active ? &m_.partition : nullptr;
  const CountedNodes counted = counted_nodes(part, ns.size());
  std::array<ExactSum, 3> F;
  for (std::uint32_t i : pm.nodes) {
    if (!(ns.flags[i] & kActive) || !counted(i)) continue;
    for (int d = 0; d < ns.dim; ++d) {
      if (!pm.component[d]) continue;
      const std::size_t dof = static_cast<std::size_t>(i) * 3 + d;
      const auto q = std::lower_bound(fixed_dofs_.begin(), fixed_dofs_.end(), dof);
      if (q != fixed_dofs_.end() && *q == dof)
        F[static_cast<std::size_t>(d)].add(reaction_[static_cast<std::size_t>(q - fixed_dofs_.begin())] *
                                           ns.volume[i]);
    }
  }
  add_over_ranks(part, F.data(), F.size());
  return {F[0].value(), F[1].value(), F[2].value()};
}

std::array<double, 3> VelocityVerlet::applied_force(const BodyLoad& load) const {
  const NodeSet& ns = m_.nodes;
  double volume = 0;
  for (std::uint32_t i : load.nodes)
    if (ns.flags[i] & kActive) volume += ns.volume[i];
  const double amp = load.amplitude(time_);
  return {amp * load.density[0] * volume, amp * load.density[1] * volume,
          amp * load.density[2] * volume};
}

double VelocityVerlet::external_power() const {
  const NodeSet& ns = m_.nodes;
  // Owned integration: each rank sums the terms of its own nodes (another rank's may be stale
  // here) and the ranks add their exact sums: the serial sum to the bit.
  const RowPartition& part = m_.partition;
  const bool owned = part.ghost_mode && part.mine.size() == ns.size();
  if (m_.loads.empty() && fixed_dofs_.empty()) return 0.0;
  ExactSum p;
  for (const BodyLoad& L : m_.loads)
    for (std::uint32_t i : L.nodes)
      if (!owned || part.mine[i])
        for (int d = 0; d < ns.dim; ++d) p.add(body_[d][i] * ns.v[d][i] * ns.volume[i]);
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q) {
    const std::size_t i = fixed_dofs_[q] / 3;
    const int d = static_cast<int>(fixed_dofs_[q] % 3);
    if (!owned || part.mine[i]) p.add(reaction_[q] * ns.v[d][i] * ns.volume[i]);
  }
  if (owned) mpi::sum_exact(&p, 1);
  return p.value();
}

void VelocityVerlet::initialize() {
  impose_motions(time_, false);
  NodeSet& ns = m_.nodes;
  ns.sync_all_current();
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q)
    v_prev_fixed_[q] = ns.v[fixed_dofs_[q] % 3][fixed_dofs_[q] / 3];
  apply_loads(time_);
  compute_accelerations();
  classify_rates(nullptr);
  last_power_ = external_power();
}

void VelocityVerlet::refresh(const std::vector<std::uint32_t>* rows, bool sync) {
  if (sync) sync_state();
  ghost_step_ = false;
  m_.nodes.sync_all_current();
  apply_loads(time_);
  // State-based, the rows' neighbours read their changed dilatations: their forces change too.
  // A step whose energy densities are wanted takes a full pass: the force pass forms them in
  // another order than the energy pass, which a distributed run's observers would take after a
  // partial one (serial and distributed runs write the same bits).
  if (rows && m_.formulation.state_based() && m_.formulation.refreshes_rows()) {
    if (energy_wanted()) {
      compute_accelerations(nullptr);
    } else {
      const std::vector<std::uint32_t> reading = rows_reading(m_, *rows);
      compute_accelerations(&reading);
    }
  } else {
    compute_accelerations(rows);
  }
  // A node's rate changes only with its row (new nodes, rebuilt families, scaled horizons).
  classify_rates(rows);
  if (syncing_) {
    // The nodes that go on with their cycle get a half-step velocity again, from their
    // acceleration now: a row the event rebuilt thus runs the rest of its cycle under its new
    // forces (with the old acceleration it would mix the two over the whole cycle, a first-order
    // error for cycles of 3 dt or more); for the other rows it is the one taken off.
    NodeSet& ns = m_.nodes;
    for (const Synced& q : synced_)
      if (rate_[q.node] == q.rate) {
        const double c = (0.5 * q.rate - static_cast<double>(step_ % q.rate)) * dt_;
        for (int d = 0; d < ns.dim; ++d) ns.v[d][q.node] += c * ns.a[d][q.node];
      }
    synced_.clear();
    syncing_ = false;
  }
  last_power_ = external_power();
}

void VelocityVerlet::undo_last_step() {
  NodeSet& ns = m_.nodes;
  const std::size_t n = saved_.broken_weight.size();
  for (int d = 0; d < ns.dim; ++d) {
    std::copy(saved_.u[d].begin(), saved_.u[d].end(), ns.u[d].begin());
    std::copy(saved_.v[d].begin(), saved_.v[d].end(), ns.v[d].begin());
    std::copy(saved_.a[d].begin(), saved_.a[d].end(), ns.a[d].begin());
  }
  std::copy(saved_.broken_weight.begin(), saved_.broken_weight.end(), ns.broken_weight.begin());
  for (std::uint64_t k : saved_.broken_log) m_.bonds.beta[k] = std::abs(m_.bonds.beta[k]);
  if (m_.bonds.keeps_state) m_.bonds.state = saved_.bond_state;
  saved_.broken_log.clear();
  for (std::size_t i = 0; i < n; ++i) ns.sync_current(i);
  v_prev_fixed_ = saved_.v_prev_fixed;
  reaction_ = saved_.reaction;
  time_ = saved_.time;
  step_ = saved_.step;
  external_work_ = saved_.external_work;
  last_power_ = saved_.last_power;
  broken_total_ = saved_.broken_total;
  bond_evals_ = saved_.bond_evals;
  m_.impactors = saved_.impactors;
  // The step is taken again: it counts once among the steps that advanced the regions alone.
  if (ghost_step_) --m_.partition.region_steps;
}

std::vector<std::uint32_t> VelocityVerlet::rows_damaged_by_last_step() const {
  const NodeSet& ns = m_.nodes;
  std::vector<std::uint32_t> out;
  const std::size_t n = std::min(saved_.broken_weight.size(), ns.size());
  for (std::size_t i = 0; i < n; ++i)
    if (ns.broken_weight[i] > saved_.broken_weight[i] && ns.family_weight[i] > 0)
      out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

bool VelocityVerlet::enable_owned_integration() {
  RowPartition& p = m_.partition;
  p.ghost_mode = p.active && !m_.contact.enabled && m_.impactors.empty() && !m_.pdro.enabled &&
                 !m_.ghost.enabled;
  return p.ghost_mode;
}

void VelocityVerlet::sync_state() {
  if (!stale_) return;
  NodeSet& ns = m_.nodes;
  // Per-row values each owner keeps for its rows: the stretch trigger's, and multi-rate's
  // latest energy densities (a repartition after an event hands rows to new owners).
  std::vector<std::vector<double>*> per_row;
  if (m_.track_breakable_stretch && m_.breakable_stretch.size() == ns.size())
    per_row.push_back(&m_.breakable_stretch);
  if (multirate_ && energy_check_every_ > 0 && energy_.size() == ns.size())
    per_row.push_back(&energy_);
  const long fields = static_cast<long>(per_row.size());
  if (mpi::max(fields) != -mpi::max(-fields))
    throw std::logic_error("owned integration: the ranks keep different per-row fields");
  gather_owned_state(m_.partition, ns, per_row);
  // The prescribed components' reactions and start-of-step velocities, from their owners.
  const RowPartition& part = m_.partition;
  std::vector<double> mine;
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q)
    if (part.mine[fixed_dofs_[q] / 3]) {
      mine.push_back(reaction_[q]);
      mine.push_back(v_prev_fixed_[q]);
    }
  std::vector<int> counts;
  const std::vector<double> all = mpi::all_gather(mine, &counts);
  std::vector<std::size_t> at(counts.size(), 0);
  for (std::size_t r = 1; r < counts.size(); ++r) at[r] = at[r - 1] + static_cast<std::size_t>(counts[r - 1]);
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q) {
    const auto r = static_cast<std::size_t>(part.owner[fixed_dofs_[q] / 3]);
    reaction_[q] = all[at[r]++];
    v_prev_fixed_[q] = all[at[r]++];
  }
  stale_ = false;
}

void VelocityVerlet::sync_nodes(const std::vector<std::uint32_t>& ids) {
  if (stale_) sync_from(m_.partition.owner, &ids);
}

void VelocityVerlet::sync_state_from(const std::vector<int>& owner) {
  if (!stale_) return;
  sync_from(owner, nullptr);
  stale_ = false;
}

void VelocityVerlet::sync_from(const std::vector<int>& owner, const std::vector<std::uint32_t>* ids) {
  NodeSet& ns = m_.nodes;
  const int D = ns.dim, me = mpi::rank();
  // The per-row values owners keep (sync_state()), as far as the owners' list reaches: an
  // event's new rows have none yet.
  std::vector<std::vector<double>*> per_row;
  if (m_.track_breakable_stretch && m_.breakable_stretch.size() >= owner.size())
    per_row.push_back(&m_.breakable_stretch);
  if (multirate_ && energy_check_every_ > 0 && energy_.size() >= owner.size())
    per_row.push_back(&energy_);
  const std::size_t width = 4 * static_cast<std::size_t>(D) + per_row.size();
  // Each rank's nodes in the set, in id order: what every rank knows of the others' lists.
  std::vector<std::vector<std::uint32_t>> of(static_cast<std::size_t>(mpi::size()));
  std::vector<char> in_set(ns.size(), 0);
  auto take = [&](std::size_t i) {
    if (i >= owner.size() || owner[i] < 0) return;
    of[static_cast<std::size_t>(owner[i])].push_back(static_cast<std::uint32_t>(i));
    in_set[i] = 1;
  };
  if (ids)
    for (std::uint32_t i : *ids) take(i);
  else
    for (std::size_t i = 0; i < owner.size(); ++i) take(i);
  std::vector<double> values;
  values.reserve(of[static_cast<std::size_t>(me)].size() * width);
  for (std::uint32_t i : of[static_cast<std::size_t>(me)]) {
    for (const auto* field : {&ns.u, &ns.v, &ns.a, &ns.f})
      for (int d = 0; d < D; ++d) values.push_back((*field)[d][i]);
    for (const std::vector<double>* w : per_row) values.push_back((*w)[i]);
  }
  // The prescribed components' reactions and start-of-step velocities of those nodes.
  std::vector<double> fixed;
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q) {
    const std::size_t i = fixed_dofs_[q] / 3;
    if (in_set[i] && owner[i] == me) {
      fixed.push_back(reaction_[q]);
      fixed.push_back(v_prev_fixed_[q]);
    }
  }
  std::vector<int> counts, fixed_counts;
  const std::vector<double> all = mpi::all_gather(values, &counts);
  const std::vector<double> all_fixed = mpi::all_gather(fixed, &fixed_counts);
  std::size_t at = 0;
  for (std::size_t r = 0; r < of.size(); ++r) {
    if (static_cast<int>(r) == me) {
      at += of[r].size() * width;
      continue;
    }
    for (std::uint32_t i : of[r]) {
      const double* v = &all[at];
      at += width;
      for (auto* field : {&ns.u, &ns.v, &ns.a, &ns.f})
        for (int d = 0; d < D; ++d) (*field)[d][i] = *v++;
      for (std::vector<double>* w : per_row) (*w)[i] = *v++;
      ns.sync_current(i);
    }
  }
  std::vector<std::size_t> fat(fixed_counts.size(), 0);
  for (std::size_t r = 1; r < fixed_counts.size(); ++r)
    fat[r] = fat[r - 1] + static_cast<std::size_t>(fixed_counts[r - 1]);
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q) {
    const std::size_t i = fixed_dofs_[q] / 3;
    if (!in_set[i]) continue;
    const auto r = static_cast<std::size_t>(owner[i]);
    if (static_cast<int>(r) != me) {
      reaction_[q] = all_fixed[fat[r]];
      v_prev_fixed_[q] = all_fixed[fat[r] + 1];
    }
    fat[r] += 2;
  }
}

bool VelocityVerlet::region_step_allowed() {
  const RowPartition& p = m_.partition;
  // The region comes with the partition, made by a force pass (after a restart: the first step's).
  // (The same answer on every rank: they hold the same partition.)
  if (!p.ghost_mode || p.region_generation != p.generation || p.nodes != m_.nodes.size() ||
      p.bonds != m_.bonds.neighbor.size())
    return false;
  // A pass that computes energy densities shares them for every row (the observers and the
  // energy trigger read them all): such steps run whole, after a sync. Only rank 0's observers
  // may ask, so the ranks agree first.
  const long next = step_ + 1;
  const bool want_energy =
      std::find(energy_requests_.begin(), energy_requests_.end(), next) != energy_requests_.end();
  const long every = energy_check_every_;
  const bool keep_recent = multirate_ && every > 0 && (every - next % every) % every < max_ratio_;
  return mpi::max(want_energy || (keep_recent && !owned_energy_checks_)) == 0;
}

bool VelocityVerlet::step() {
  NodeSet& ns = m_.nodes;
  const std::size_t n = ns.size();
  const int dim = ns.dim;
  const double dt = dt_, hdt = 0.5 * dt_;
  ghost_step_ = region_step_allowed();
  if (!ghost_step_) sync_state();
  m_.partition.region_steps += ghost_step_;
  const std::vector<std::uint32_t>* region = ghost_step_ ? &m_.partition.region : nullptr;
  // Kicks and drift go in one pass over the nodes (one thread fork per step, not 2 dim), which
  // also keeps the state an undo needs on the way; components with a prescribed velocity are
  // put on it afterwards.
  if (undo_enabled_) {
    // Components beyond the model's dimension stay zero: nothing to keep.
    for (int d = 0; d < dim; ++d) {
      saved_.u[d].resize(n);
      saved_.v[d].resize(n);
      saved_.a[d].resize(n);
    }
    saved_.broken_weight = ns.broken_weight;
    saved_.v_prev_fixed = v_prev_fixed_;
    saved_.reaction = reaction_;
    saved_.time = time_;
    saved_.step = step_;
    saved_.external_work = external_work_;
    saved_.last_power = last_power_;
    saved_.broken_total = broken_total_;
    saved_.bond_evals = bond_evals_;
    saved_.broken_log.clear();
    if (m_.bonds.keeps_state) saved_.bond_state = m_.bonds.state;
    saved_.impactors = m_.impactors;
  }
  for (std::size_t q = 0; q < fixed_dofs_.size(); ++q)
    v_prev_fixed_[q] = ns.v[fixed_dofs_[q] % 3][fixed_dofs_[q] / 3];
  // Multi-rate stepping: this step's kicks per rate and the rows whose step closes now.
  prepare_rates();
  // Rigid impactors: the same kick and drift as the nodes. What they lose in kinetic energy is
  // work done on the body (external_work).
  double impactor_energy = 0;
  for (Impactor& im : m_.impactors) {
    impactor_energy += im.kinetic_energy();
    im.velocity = add(im.velocity, scale(im.force, hdt / im.mass));
    im.center = add(im.center, scale(im.velocity, dt));
  }

  // Half-step velocity, then positions; motions with prescribed velocity use v(t + dt/2).
  const double lim = runaway_limit_;
  std::size_t bad = n;
  // Displacements before the drift of the components driven by a prescribed velocity.
  driven_u_.clear();
  for (const PrescribedMotion& pm : m_.motions)
    if (pm.kind == PrescribedMotion::Kind::Velocity)
      for (std::uint32_t i : pm.nodes)
        for (int d = 0; d < dim; ++d)
          if (pm.component[d] && !outside_region(i)) driven_u_.push_back(ns.u[d][i]);
  const StepArrays sa = arrays();
  std::size_t nbad = with_dim(dim, [&](auto D) {
    return with_bool(undo_enabled_, [&](auto K) {
      return with_bool(sa.rate != nullptr, [&](auto M) {
        return with_bool(region != nullptr, [&](auto L) {
          return kick_drift<D(), K(), M(), L()>(sa, region ? region->data() : nullptr,
                                                region ? region->size() : n, open_kick_.data(), hdt,
                                                dt, lim);
        });
      });
    });
  });
  if (!driven_u_.empty()) {
    // Their half-step velocity is the prescribed one, v(t + dt/2), and their drift follows it.
    impose_motions(time_ + hdt, true);
    std::size_t q = 0;
    for (const PrescribedMotion& pm : m_.motions)
      if (pm.kind == PrescribedMotion::Kind::Velocity)
        for (std::uint32_t i : pm.nodes)
          for (int d = 0; d < dim; ++d)
            if (pm.component[d] && !outside_region(i)) {
              ns.u[d][i] = driven_u_[q++] + dt * ns.v[d][i];
              ns.cur[4 * static_cast<std::size_t>(i) + d] = ns.x[d][i] + ns.u[d][i];
              nbad += !(std::abs(ns.u[d][i]) <= lim);
            }
  }
  // Rare: find the first offending node for the diagnosis.
  if (region) {
    stale_ = true;
    for (std::size_t r = 0; nbad > 0 && r < region->size() && bad == n; ++r)
      for (int d = 0; d < dim; ++d)
        if (!(std::abs(ns.u[d][(*region)[r]]) <= lim)) bad = (*region)[r];
    // Every node is in its owner's region: the lowest offending node over the ranks.
    bad = static_cast<std::size_t>(-mpi::max(-static_cast<long>(bad)));
  } else {
    for (std::size_t i = 0; nbad > 0 && i < n && bad == n; ++i)
      for (int d = 0; d < dim; ++d)
        if (!(std::abs(ns.u[d][i]) <= lim)) bad = i;
  }
  time_ += dt;
  ++step_;
  impose_motions(time_, false);
  for (const PrescribedMotion& pm : m_.motions)
    if (pm.kind == PrescribedMotion::Kind::Displacement)
      for (std::uint32_t i : pm.nodes)
        ns.sync_current(i);
  if (bad < n) {
    sync_state();
    divergence_ = {bad, step_, time_,
                   std::isfinite(ns.u[0][bad]) ? "displacement exceeds 100x the body size"
                                               : "non-finite displacement"};
    return false;
  }

  apply_loads(time_);
  if (multirate_ && !full_pass_)
    compute_accelerations(&pass_rows_, true, true);
  else
    compute_accelerations(nullptr, false, true);
  impose_motions(time_, true);
  for (Impactor& im : m_.impactors) {
    im.velocity = add(im.velocity, scale(im.force, hdt / im.mass));
    impactor_energy -= im.kinetic_energy();
  }
  const double p = external_power();
  // An impactor's state is solver state too: one that runs away (an absurd speed) would put NaN
  // into the external work and the energy balance without any node diverging.
  for (std::size_t k = 0; k < m_.impactors.size(); ++k) {
    const Impactor& im = m_.impactors[k];
    bool finite = std::isfinite(im.kinetic_energy());
    for (int d = 0; d < 3; ++d) finite = finite && std::isfinite(im.center[d]) && std::isfinite(im.force[d]);
    if (!finite) {
      divergence_ = {0, step_, time_,
                     "impactors[" + std::to_string(k) +
                         "]: non-finite position, velocity or force (speed too large for the "
                         "time step?)"};
      return false;
    }
  }
  external_work_ += 0.5 * (p + last_power_) * dt + impactor_energy;
  last_power_ = p;
  return true;
}

}  // namespace periadapt
