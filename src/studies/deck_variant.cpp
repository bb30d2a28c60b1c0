#include "studies/deck_variant.hpp"

#include <fstream>
#include <sstream>

#include "input/deck_error.hpp"

namespace periadapt {

Deck deck_variant(const std::string& path, const std::string& label,
                  const std::function<void(YAML::Node&)>& edit) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw DeckError(path, 0, 0, "", "cannot open the study's deck (run from the repository root "
                                    "or pass --deck)");
  } catch (const YAML::Exception& e) {
    throw DeckError(path, e.mark.line + 1, e.mark.column + 1, "", e.msg);
  }
  edit(root);
  YAML::Emitter em;
  em << root;
  return parse_deck(em.c_str(), path + " (" + label + ")");
}

}  // namespace periadapt
