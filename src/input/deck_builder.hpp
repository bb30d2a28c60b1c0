#pragma once
// Builds a deck in code (studies, tests, benchmarks) instead of formatting YAML text: keys are
// set by their dotted paths, list entries appended as builders of their own, and build() runs
// the same loader and checks as a deck file (a bad value is a DeckError naming its key).
//   Deck dk = DeckBuilder()
//                 .set("model.dimension", 2)
//                 .set("material.youngs_modulus", 72e9)
//                 .set("discretization.body.box.min", {0.0, 0.0})
//                 .append("loads", DeckBuilder().set("name", "top").set("type", "traction"))
//                 .build();
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "input/deck.hpp"

namespace periadapt {

class DeckBuilder {
 public:
  DeckBuilder();
  DeckBuilder& set(std::string_view path, double value);
  DeckBuilder& set(std::string_view path, int value);
  DeckBuilder& set(std::string_view path, bool value);
  DeckBuilder& set(std::string_view path, const char* value);
  DeckBuilder& set(std::string_view path, const std::string& value);
  DeckBuilder& set(std::string_view path, std::initializer_list<double> values);
  DeckBuilder& set(std::string_view path, const std::vector<double>& values);
  DeckBuilder& set(std::string_view path, const std::vector<std::string>& values);
  // A list of points (a crack segment, a polygon).
  DeckBuilder& set(std::string_view path, const std::vector<std::vector<double>>& points);
  // A list whose empty entries are YAML nulls (a component left free: `velocity: [expr, null]`).
  DeckBuilder& set(std::string_view path, const std::vector<std::optional<std::string>>& values);
  // A sub-tree (a region, a section) built on its own.
  DeckBuilder& set(std::string_view path, const DeckBuilder& tree);
  // Appends an entry to the list at `path` (loads, boundary_conditions, cracks, damage.no_fail).
  DeckBuilder& append(std::string_view path, const DeckBuilder& entry);

  // The deck as YAML text (what build() reads), and the validated deck.
  std::string yaml() const;
  Deck build(const std::string& name = "built deck") const;

 private:
  YAML::Node at(std::string_view path);
  YAML::Node root_;
};

}  // namespace periadapt
