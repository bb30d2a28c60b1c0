#pragma once
// Deck -> Model: grid, horizons, material constants, families, pre-cracks, loads, motions and
// initial fields. Throws DeckError when a deck entry cannot be realised (e.g. an empty region).
#include "input/deck.hpp"
#include "model/model.hpp"

namespace periadapt {

Model build_model(const Deck& deck);

}  // namespace periadapt
