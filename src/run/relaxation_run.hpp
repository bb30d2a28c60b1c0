#pragma once
// A quasi-static run by adaptive dynamic relaxation (solver.type: relaxation): load steps with
// bond breaking; a VTU snapshot and a history row per load step, summary.json.
#include "run/simulation.hpp"

namespace periadapt {

RunResult run_relaxation(const Deck& deck, const RunOptions& opt);

}  // namespace periadapt
