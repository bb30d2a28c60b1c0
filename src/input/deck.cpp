// The deck loader: reads the YAML (with --set overrides), then the section parsers of
// input/deck_sections.hpp in order.
#include "input/deck.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "input/yaml_section.hpp"

namespace periadapt {

namespace {
Deck parse_deck_sections(const std::string& text, const std::string& name,
                         const std::vector<std::string>& overrides);

// A copy without source marks: an error on an overridden key names the key, not a line of the
// deck file (the value came from the command line).
YAML::Node unmarked(const YAML::Node& n) {
  if (n.IsScalar()) return YAML::Node(n.Scalar());
  // An empty list or mapping keeps its kind (`--set cracks={}` is a mapping, not "no cracks").
  YAML::Node out(n.IsSequence() ? YAML::NodeType::Sequence
                 : n.IsMap()    ? YAML::NodeType::Map
                                : YAML::NodeType::Null);
  if (n.IsSequence())
    for (const YAML::Node& e : n) out.push_back(unmarked(e));
  else if (n.IsMap())
    for (const auto& kv : n) out[unmarked(kv.first)] = unmarked(kv.second);
  return out;
}

// Sets root[a][b]... = value for one "a.b...=value" override.
void apply_override(YAML::Node root, const std::string& name, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0)
    throw DeckError(name, 0, 0, "", "--set '" + kv + "': expected key.path=value");
  const std::string path = kv.substr(0, eq);
  std::vector<std::string> keys;
  for (std::size_t b = 0;;) {
    const auto dot = path.find('.', b);
    keys.push_back(path.substr(b, dot == std::string::npos ? std::string::npos : dot - b));
    if (keys.back().empty())
      throw DeckError(name, 0, 0, "", "--set '" + kv + "': empty key in the path");
    if (dot == std::string::npos) break;
    b = dot + 1;
  }
  YAML::Node value;
  try {
    value = unmarked(YAML::Load(kv.substr(eq + 1)));
  } catch (const YAML::Exception& e) {
    throw DeckError(name, 0, 0, path, "--set: the value is not YAML: " + e.msg);
  }
  YAML::Node node = root;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string& key = keys[k];
    const bool last = k + 1 == keys.size();
    if (node.IsSequence()) {
      const bool digits = key.find_first_not_of("0123456789") == std::string::npos;
      const std::size_t at = digits && key.size() < 10 ? std::stoul(key) : node.size();
      if (at >= node.size())
        throw DeckError(name, 0, 0, path,
                        "--set: '" + key + "' is not an index of that list (0 ... " +
                            std::to_string(node.size()) + " - 1)");
      if (last) {
        node[at] = value;
        return;
      }
      node.reset(node[at]);
      continue;
    }
    if (!node.IsMap() && !node.IsNull())
      throw DeckError(name, 0, 0, path, "--set: '" + key + "' is below a single value");
    if (last) {
      node[key] = value;
      return;
    }
    if (!node[key]) node[key] = YAML::Node(YAML::NodeType::Map);
    node.reset(node[key]);
  }
}
}  // namespace

Deck parse_deck(const std::string& text, const std::string& name,
                const std::vector<std::string>& overrides) {
  // Every path out of the loader is a DeckError: a yaml-cpp exception that a section's own
  // checks did not turn into one still names the file and the line.
  try {
    return parse_deck_sections(text, name, overrides);
  } catch (const YAML::Exception& e) {
    throw DeckError(name, e.mark.is_null() ? 0 : e.mark.line + 1,
                    e.mark.is_null() ? 0 : e.mark.column + 1, "",
                    "cannot read this YAML: " + e.msg);
  }
}

namespace {
// yaml-cpp keeps both entries of a repeated key and reads the first: the second would be
// ignored without a word.
void refuse_duplicate_keys(const YAML::Node& n, const std::string& name, const std::string& path) {
  if (n.IsMap()) {
    std::map<std::string, int> seen;
    for (auto it = n.begin(); it != n.end(); ++it) {
      const bool scalar = it->first.IsScalar();
      const std::string key = scalar ? it->first.Scalar() : std::string("?");
      const std::string at = path.empty() ? key : path + "." + key;
      if (scalar) {
        const auto [first, fresh] = seen.emplace(key, it->first.Mark().line + 1);
        if (!fresh)
          throw DeckError(name, it->first.Mark().line + 1, it->first.Mark().column + 1, at,
                          "given twice in one mapping (first on line " +
                              std::to_string(first->second) +
                              "); a key may appear once, and the second would be ignored");
      }
      refuse_duplicate_keys(it->second, name, at);
    }
  } else if (n.IsSequence()) {
    for (std::size_t k = 0; k < n.size(); ++k)
      refuse_duplicate_keys(n[k], name, path + "[" + std::to_string(k) + "]");
  }
}

// The line of the document marker ('---' or '...' at the start of a line) that a second
// document with content follows, or 0. By lines, as YAML marks documents: yaml-cpp 0.7's LoadAll
// loops without end on some malformed streams (the deck fuzzer's timeout, `# x` then `, b`).
int second_document_line(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0, boundary = 0;
  bool content = false;
  auto has_content = [](const std::string& s) {
    const auto p = s.find_first_not_of(" \t");
    return p != std::string::npos && s[p] != '#';
  };
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const bool marker = (line.rfind("---", 0) == 0 || line.rfind("...", 0) == 0) &&
                        (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
    const std::string rest = marker ? line.substr(3) : line;
    if (marker && content && !boundary) boundary = n;
    if (!has_content(rest)) continue;
    if (boundary) return boundary;
    content = true;
  }
  return 0;
}

Deck parse_deck_sections(const std::string& text, const std::string& name,
                         const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw DeckError(name, e.mark.line + 1, e.mark.column + 1, "",
                    "malformed YAML: " + e.msg + " (check indentation, colons and brackets)");
  }
  if (const int line = second_document_line(text))
    throw DeckError(name, line, 1, "",
                    "a second YAML document (after '---' or '...'): a deck is one document, and "
                    "what follows the first would be ignored");
  refuse_duplicate_keys(root, name, "");
  if (root.IsMap())
    for (const std::string& kv : overrides) apply_override(root, name, kv);
  if (!root.IsMap())
    throw DeckError(name, 0, 0, "", "a deck is a YAML mapping with sections model, material, "
                                    "discretization, ... (see docs/deck-reference.md)");
  Deck dk;
  dk.file = name;
  deck_sections::set_deck_folder(std::filesystem::path(name).parent_path());
  {
    // What a checkpoint must agree with: the deck without its output section and run length
    // (a restart may write elsewhere or run longer), comments and layout aside.
    YAML::Node physics = YAML::Clone(root);
    physics.remove("output");
    if (const YAML::Node& cp = physics; cp["solver"] && cp["solver"].IsMap()) {
      physics["solver"].remove("end_time");
      physics["solver"].remove("steps");
    }
    dk.physics_text = YAML::Dump(physics);
  }
  Section top(root, "", name);

  deck_sections::parse_model_and_material(top, dk);
  deck_sections::parse_discretization_and_cracks(top, dk);
  deck_sections::parse_loading_and_damage(top, dk);
  deck_sections::parse_solver(top, dk);
  deck_sections::parse_blocks(top, dk);
  deck_sections::parse_adapt(top, dk);
  deck_sections::parse_output(top, dk);
  top.finish();
  return dk;
}
}  // namespace

Deck load_deck(const std::string& path, const std::vector<std::string>& overrides) {
  // A deck is a small text file: a device, a pipe or a folder would be read without bound.
  constexpr std::uintmax_t kMaxDeckBytes = 16u << 20;
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw DeckError(path, 0, 0, "", "cannot open the deck file");
  if (!std::filesystem::is_regular_file(status))
    throw DeckError(path, 0, 0, "", "is not a regular file; a deck is a YAML text file");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > kMaxDeckBytes)
    throw DeckError(path, 0, 0, "",
                    "the file has " + std::to_string(bytes) + " bytes; a deck has at most " +
                        std::to_string(kMaxDeckBytes) + " (16 MiB)");
  std::ifstream in(path);
  if (!in) throw DeckError(path, 0, 0, "", "cannot open the deck file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_deck(ss.str(), path, overrides);
}

}  // namespace periadapt
