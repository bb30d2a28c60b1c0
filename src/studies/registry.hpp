#pragma once
// The built-in studies of the seeds, by name: `periadapt study NAME` looks them up here. A new
// study is its own file plus one row of the table in registry.cpp.
#include <string>
#include <vector>

namespace periadapt {

// Command-line options a study may read (each ignores those it has no use for).
struct StudyOptions {
  std::string out_dir;
  std::string deck;          // the deck a deck-based study varies ("" = its default)
  bool quick = false;        // a shorter version for checks
  bool pim = false;          // pdro-*: overlay interpolation by PIM
  bool gaussian = false;     // pdro-*: Gaussian PDDO weight
  bool whole_bond = false;   // pdro-*: sub-pairs over the whole bond
};

struct Study {
  const char* name;
  const char* what;  // one line for --help
  int (*run)(const StudyOptions&);
};

const std::vector<Study>& studies();
// nullptr for an unknown name.
const Study* find_study(const std::string& name);

}  // namespace periadapt
