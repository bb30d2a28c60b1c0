#pragma once
// The CSV a study writes beside its printed table: OUT_DIR/name with its header line (the
// directory is created). With no output directory the stream stays closed and `if (csv)` skips
// the rows.
#include <filesystem>
#include <fstream>
#include <string>

namespace periadapt {

inline std::ofstream open_study_csv(const std::string& out_dir, const std::string& name,
                                    const std::string& header) {
  std::ofstream csv;
  if (out_dir.empty()) return csv;
  std::filesystem::create_directories(out_dir);
  csv.open(out_dir + "/" + name);
  csv << header << "\n";
  return csv;
}

}  // namespace periadapt
