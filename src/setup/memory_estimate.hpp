#pragma once
// What a deck will allocate, estimated from the deck alone (before any grid is generated), so
// that `check` and `run` refuse impossible work at once instead of growing until the machine
// kills them.
#include <cstddef>

#include "input/deck.hpp"

namespace periadapt {

struct MemoryEstimate {
  double nodes = 0;     // grid nodes, initial refinement included (holes not subtracted)
  double bonds = 0;     // directed bond entries
  double bytes = 0;     // model arrays: nodes, bonds (with AGRS's spare quarter), transposes
  double available = 0; // the machine's available memory (bytes; 0 where unknown)
};

MemoryEstimate estimate_memory(const Deck& deck);

// Throws DeckError with the estimate when it exceeds the available memory, solver.memory_limit_gb
// or 2^31 nodes.
void check_memory_estimate(const Deck& deck);

}  // namespace periadapt
