#pragma once
// A study's runs as edits of one example deck: the deck file is read as YAML, `edit` changes some
// keys (grid spacing, overlay, outputs), and the result is validated like any deck, so the
// study and the example a user runs by hand cannot drift apart.
#include <functional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "input/deck.hpp"

namespace periadapt {

Deck deck_variant(const std::string& path, const std::string& label,
                  const std::function<void(YAML::Node&)>& edit);

}  // namespace periadapt
