#pragma once
// The history.csv column stem of a named load or boundary condition: the prefix, then the name
// with every character other than a letter or digit replaced by '_' (spreadsheets and
// plotting tools read such headers without quoting). Two names with the same stem would share
// columns, so the deck reader compares stems, not names.
#include <cctype>
#include <string>

namespace periadapt {

inline std::string csv_column_stem(const std::string& prefix, const std::string& name) {
  std::string s = prefix;
  for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

}  // namespace periadapt
