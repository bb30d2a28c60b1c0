#pragma once
// A static run (solver.type: static): linearized bond-based equilibrium under the deck's loads at
// full amplitude and its displacement conditions; writes a VTU snapshot, displacement.csv and
// summary.json.
#include "run/simulation.hpp"

namespace periadapt {

RunResult run_static(const Deck& deck, const RunOptions& opt);

}  // namespace periadapt
