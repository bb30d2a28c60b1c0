#include "input/deck_builder.hpp"

#include <fmt/format.h>

#include "input/deck_error.hpp"

namespace periadapt {

namespace {

// Shortest decimals that read back to the same double.
std::string number(double v) { return fmt::format("{}", v); }

}  // namespace

DeckBuilder::DeckBuilder() : root_(YAML::NodeType::Map) {}

YAML::Node DeckBuilder::at(std::string_view path) {
  YAML::Node node = root_;
  std::size_t b = 0;
  for (;;) {
    const std::size_t dot = path.find('.', b);
    const std::string key(path.substr(b, dot == std::string_view::npos ? std::string_view::npos : dot - b));
    if (key.empty()) throw DeckError("built deck", 0, 0, std::string(path), "empty key in the path");
    if (dot == std::string_view::npos) {
      YAML::Node leaf = node[key];
      return leaf;
    }
    if (!node[key] || !node[key].IsMap()) node[key] = YAML::Node(YAML::NodeType::Map);
    node.reset(node[key]);
    b = dot + 1;
  }
}

DeckBuilder& DeckBuilder::set(std::string_view path, double value) {
  at(path) = number(value);
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, int value) {
  at(path) = std::to_string(value);
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, bool value) {
  at(path) = value ? "true" : "false";
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, const char* value) {
  return set(path, std::string(value));
}
DeckBuilder& DeckBuilder::set(std::string_view path, const std::string& value) {
  at(path) = value;
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, std::initializer_list<double> values) {
  return set(path, std::vector<double>(values));
}
DeckBuilder& DeckBuilder::set(std::string_view path, const std::vector<double>& values) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (double v : values) list.push_back(number(v));
  at(path) = list;
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, const std::vector<std::string>& values) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const std::string& v : values) list.push_back(v);
  at(path) = list;
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, const std::vector<std::vector<double>>& points) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const auto& p : points) {
    YAML::Node point(YAML::NodeType::Sequence);
    for (double v : p) point.push_back(number(v));
    list.push_back(point);
  }
  at(path) = list;
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path,
                              const std::vector<std::optional<std::string>>& values) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const auto& v : values) list.push_back(v ? YAML::Node(*v) : YAML::Node(YAML::NodeType::Null));
  at(path) = list;
  return *this;
}
DeckBuilder& DeckBuilder::set(std::string_view path, const DeckBuilder& tree) {
  at(path) = YAML::Clone(tree.root_);
  return *this;
}
DeckBuilder& DeckBuilder::append(std::string_view path, const DeckBuilder& entry) {
  YAML::Node list = at(path);
  if (!list.IsSequence()) list = YAML::Node(YAML::NodeType::Sequence);
  list.push_back(YAML::Clone(entry.root_));
  return *this;
}

std::string DeckBuilder::yaml() const {
  YAML::Emitter out;
  out << root_;
  return std::string(out.c_str()) + "\n";
}

Deck DeckBuilder::build(const std::string& name) const { return parse_deck(yaml(), name); }

}  // namespace periadapt
