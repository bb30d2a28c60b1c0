#pragma once
// periadapt sweep: one deck run for every combination of the values given to its keys, each in
// its own folder, and sweep.csv with one row of results per run.
#include <string>
#include <vector>

namespace periadapt {

// `sets`: "key.path=v1,v2,..." (commas inside brackets or braces belong to a value); `fixed`:
// plain --set overrides applied to every run. Returns the exit code (0 when every run completed,
// else the first failing run's code).
int run_sweep(const std::string& deck, const std::vector<std::string>& sets,
              const std::vector<std::string>& fixed, const std::string& out_dir, bool quiet);

// Splits "key=v1,v2,..." into the key and its values (top-level commas only); throws DeckError.
std::pair<std::string, std::vector<std::string>> split_sweep_values(const std::string& deck,
                                                                    const std::string& set);

}  // namespace periadapt
