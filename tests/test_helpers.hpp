#pragma once
// Small builders shared by the tests: decks from text, and models on uniform grids.
#include <string>

#include "io/deck.hpp"
#include "model/build_model.hpp"

namespace periadapt::test {

inline Deck deck_from(const std::string& yaml) { return parse_deck(yaml, "test.yaml"); }

// A minimal valid 2D deck; `extra` is appended (later keys of the same section are not merged,
// so callers pass whole sections they want to change through `sections`).
inline std::string basic_deck(const std::string& model, const std::string& material,
                              const std::string& disc, const std::string& rest) {
  return "model:\n" + model + "material:\n" + material + "discretization:\n" + disc + rest;
}

}  // namespace periadapt::test
