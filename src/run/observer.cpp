#include "run/observer.hpp"

#include "analysis/energy.hpp"
#include "solver/internal_forces.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

RunView::RunView(const Deck& dk, const Model& m, const VelocityVerlet& v, const Adaptor* a,
                 std::string d, bool write, long steps, clock::time_point start)
    : deck(dk), model(m), vv(v), adaptor(a), dir(std::move(d)), write_files(write),
      total_steps(steps), start_(start) {}

double RunView::elapsed_s() const {
  return std::chrono::duration<double>(clock::now() - start_).count();
}

bool RunView::history_due(long step, bool closing) const {
  const bool due = step % deck.output.history_every == 0 || step == total_steps;
  return closing ? !due : due;
}

void RunView::sample_energy() {
  if (energy_step_ == vv.step_count()) return;
  const std::vector<double>* w = vv.energy_density_now();
  if (!w) w = vv.energy_density_now_of_own_rows();
  if (w)
    W_ = *w;
  else
    periadapt::energy_density(model, W_);
  U_ = strain_energy_of(model.nodes, W_, model.partition.active ? &model.partition : nullptr);
  energy_step_ = vv.step_count();
}

const std::vector<double>& RunView::energy_density() {
  sample_energy();
  return W_;
}

double RunView::strain_energy() {
  sample_energy();
  return U_;
}

}  // namespace periadapt
