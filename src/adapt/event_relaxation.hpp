#pragma once
// adapt.relax_sweeps: after an event, the new nodes and the rows bonded to them are relaxed
// towards the balance the refined grid has with the current accelerations (f_i + b_i = rho_i a_i:
// the dynamic state is kept), by Jacobi sweeps on their displacements with every other node held
// and no bond breaking. The children start from the coarse grid's field, which carries its
// discretization error; without the sweeps the zone releases that error as waves (docs/agrs.md).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

// Relaxes the event's new nodes (ids from `first_new` on) and the rows bonded to them, among
// the rows it rebuilt, except those that carry a load or a prescribed motion; returns the nodes
// whose forces the sweeps changed (the relaxed rows and every row bonded to them, ascending;
// empty without sweeps).
std::vector<std::uint32_t> relax_event_rows(Model& m, const std::vector<std::uint32_t>& rebuilt,
                                            std::size_t first_new, int sweeps);

}  // namespace periadapt
