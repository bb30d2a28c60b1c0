#pragma once
// Error in an input deck: names the file, the key path, the line/column and what is allowed.
#include <stdexcept>
#include <string>

namespace periadapt {

// Where a value was given: its key path and line/column in the deck (0: not from a line, e.g. a
// --set override).
struct DeckPlace {
  std::string key;
  int line = 0, column = 0;
};

class DeckError : public std::runtime_error {
 public:
  DeckError(const std::string& file, int line, int column, const std::string& key,
            const std::string& message)
      : std::runtime_error(format(file, line, column, key, message)), key_(key), line_(line) {}
  DeckError(const std::string& file, const DeckPlace& at, const std::string& message)
      : DeckError(file, at.line, at.column, at.key, message) {}
  // An error formatted elsewhere (another rank's, passed on as it is).
  struct Formatted {};
  DeckError(Formatted, const std::string& text, const std::string& key)
      : std::runtime_error(text), key_(key), line_(0) {}
  const std::string& key() const { return key_; }
  int line() const { return line_; }

 private:
  static std::string format(const std::string& file, int line, int column, const std::string& key,
                            const std::string& message) {
    // append() rather than operator+: gcc 12 emits a false -Wrestrict on the latter.
    std::string s = file;
    if (line > 0) s.append(":").append(std::to_string(line)).append(":").append(std::to_string(column));
    s.append(": ");
    if (!key.empty()) s.append("key '").append(key).append("': ");
    s.append(message);
    return s;
  }
  std::string key_;
  int line_;
};

}  // namespace periadapt
