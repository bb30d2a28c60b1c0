#pragma once
// A static run (solver.type: static): linearized bond-based equilibrium under the deck's loads at
// full amplitude and its displacement conditions; writes a VTU snapshot, displacement.csv and
// summary.json.
#include "run/simulation.hpp"

namespace periadapt {

RunResult run_static(const Deck& deck, const RunOptions& opt);

// A static deck must prescribe some displacement: without one the body's rigid motions make the
// stiffness singular (a subtler lack is found by the solve). Throws DeckError; `check` and
// run_static both call it.
void require_held_displacements(const Deck& deck);

}  // namespace periadapt
