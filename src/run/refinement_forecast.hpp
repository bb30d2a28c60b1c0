#pragma once
// What the stretch trigger will refine before the first crack: the deck's coarse grid run
// elastically (no bond breaks, no refinement) until the first breakable bond reaches the critical
// stretch of the finest level, where the fine grid would start a crack, collecting the coarse
// nodes the trigger (with visibility and loaded neighbours) would have refined by then. `check`
// prints it and warns when that is most of the body: a uniform fine grid may then cost less.
// Refinement that follows a running crack comes on top.
#include <cstddef>

#include "input/deck.hpp"

namespace periadapt {

struct RefinementForecast {
  bool ran = false;             // within the budget, and the deck has a stretch trigger
  double bond_evaluations = 0;  // what the run costs (or would have cost)
  bool initiates = false;       // a bond reached its children's s0 (one level finer) before end_time
  double time = 0;              // when (or end_time)
  std::size_t parents = 0;      // coarse nodes the trigger would have refined by then
  std::size_t refinable = 0;
  double volume_fraction = 0;   // their share of the body's volume
};

// Runs when the deck's triggers include the stretch trigger and the run stays within
// `max_bond_evaluations` (its bonds times the steps to end_time on the coarse stable step).
RefinementForecast forecast_refinement(const Deck& deck, double max_bond_evaluations);

}  // namespace periadapt
