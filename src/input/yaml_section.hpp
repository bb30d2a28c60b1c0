#pragma once
// Typed, validating access to one YAML mapping of a deck. Every read records the key; finish()
// rejects keys nobody read, with a "did you mean" hint. Errors carry file, key path and line.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "input/deck_error.hpp"

namespace periadapt {

class Section {
 public:
  Section(YAML::Node node, std::string path, std::string file);

  bool has(const std::string& key) const;
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::string key_path(const std::string& key) const;
  DeckPlace place(const std::string& key = "") const;  // of the key, or of this section

  // Numbers. `check` returns an empty string when the value is allowed, else what is allowed.
  double number(const std::string& key, std::optional<double> fallback = std::nullopt,
                const std::function<std::string(double)>& check = {});
  long integer(const std::string& key, std::optional<long> fallback = std::nullopt,
               const std::function<std::string(long)>& check = {});
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
  std::string text(const std::string& key, std::optional<std::string> fallback = std::nullopt);
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     std::optional<std::string> fallback = std::nullopt);
  std::vector<double> numbers(const std::string& key, std::size_t min_len, std::size_t max_len);
  std::vector<std::vector<double>> points(const std::string& key, std::size_t count,
                                          std::size_t dim);
  Section section(const std::string& key);  // required mapping
  std::optional<Section> optional_section(const std::string& key);
  std::vector<Section> list(const std::string& key);  // sequence of mappings (may be absent)
  YAML::Node raw(const std::string& key);               // marks as read

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  [[noreturn]] void fail_at(const YAML::Node& n, const std::string& key,
                            const std::string& message) const;
  void finish() const;  // unknown-key check
  [[noreturn]] void missing(const std::string& key, const std::string& what) const;

 private:
  YAML::Node get(const std::string& key) const;
  YAML::Node node_;
  std::string path_, file_;
  mutable std::set<std::string> read_;
};

// Common checks.
std::function<std::string(double)> positive();
std::function<std::string(double)> non_negative();
std::function<std::string(double)> at_least(double lo);
std::function<std::string(double)> in_range(double lo, double hi);

// Levenshtein distance, for suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace periadapt
