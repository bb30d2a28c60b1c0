#pragma once
// Ghost forces at level interfaces, removed to first order in the local strain
// (adapt.ghost_correction). A row whose horizon holds cells of two sizes sums its bonds with a
// quadrature that is not exact for a linear displacement field, so a uniform strain eps pulls
// it: a force density linear in eps for small strains, G_i : eps. The table records G_i for each
// interface row, by differences of the material's own force pass from the reference positions
// under each unit strain component (so PMB and LPS alike), and every force pass then subtracts
// G_i : eps_i, eps_i the strain fitted over the row's bonds (least squares). A uniform strain
// then pulls no interface node (the patch test, bench/interface/patch_test.sh), whatever the
// formulation.
// Left alone, because a uniform strain does pull the body there: rows whose ball the cells do
// not cover (free surfaces, holes), rows with a cut bond, and, state-based, rows with such a
// neighbour (their dilatation feeds the row's force). A row stops being corrected once one of
// its bonds breaks. The correction is not the gradient of an energy: like the source-horizon
// pairing it acts on, it does not conserve energy exactly (docs/agrs.md gives the drift).
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

// Brings the table up to date with the families (all rows after set-up or a restart, the
// changed rows and, state-based, their neighbours after an event). Leaves positions, forces and
// bonds as they were.
void update_ghost_table(Model& m);

// Subtracts G_i : eps_i from the force density of the corrected rows among `rows` (all: null).
void apply_ghost_correction(Model& m, const std::vector<std::uint32_t>* rows);

}  // namespace periadapt
