#pragma once
// Deck -> Model: grid, horizons, material constants, families, pre-cracks, loads, motions and
// initial fields. Throws DeckError when a deck entry cannot be realised (e.g. an empty region).
#include <functional>

#include "input/deck.hpp"
#include "model/model.hpp"

namespace periadapt {

// How the bond families are searched: the whole model's by default; a distributed run whose ranks
// hold their own rows from the start splits the rows first and searches its own
// (parallel/held_rows.hpp), filling the model's partition.
using FamilyBuild =
    std::function<BondFamilies(const NodeSet&, const QuadratureSpec&, RowPartition&)>;

Model build_model(const Deck& deck, const FamilyBuild& families = {});

}  // namespace periadapt
