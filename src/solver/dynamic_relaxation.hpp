#pragma once
// Adaptive dynamic relaxation (Kilic & Madenci 2010) for quasi-static loading with bond breaking:
// the load (and prescribed displacements) grow in `load_steps` equal increments; at each one the
// fictitious damped dynamics  lambda v' = F - c lambda v  (diagonal fictitious density lambda from
// the bond stiffness, damping c from the Rayleigh quotient of the local stiffness) runs until the
// out-of-balance force is below `tolerance` times the applied load; then bonds above their
// critical stretch break and the same load step is relaxed again until nothing breaks.
#include <cstddef>
#include <functional>

#include "model/model.hpp"

namespace periadapt {

struct RelaxationOptions {
  int load_steps = 1;
  double tolerance = 1e-6;       // ||F|| <= tolerance ||b|| (force densities, free components)
  long max_iterations = 200000;  // per relaxation
  // Asked every few iterations (a signal): the run stops in the relaxation it is in, and the
  // state of the last converged load step is the last one reported.
  std::function<bool()> stop_requested;
};

enum class RelaxationStatus { Converged, NotConverged, Interrupted };

struct RelaxationStepReport {
  int load_step = 0;
  double load_factor = 0;
  long iterations = 0;           // summed over the relaxations of this load step
  std::size_t newly_broken = 0;
  double residual = 0;           // ||F|| / ||b|| at the end
  bool converged = false;
};

// Runs all load steps; `after_step` is called after each (for outputs), and after a relaxation
// that did not converge within max_iterations (NotConverged; the model keeps its last state).
RelaxationStatus run_dynamic_relaxation(Model& m, const RelaxationOptions& opt,
                            const std::function<void(const RelaxationStepReport&)>& after_step);

}  // namespace periadapt
