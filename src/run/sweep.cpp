#include "run/sweep.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "input/deck.hpp"
#include "input/deck_error.hpp"
#include "io/atomic_output.hpp"
#include "run/interrupt.hpp"
#include "run/simulation.hpp"

namespace periadapt {

std::pair<std::string, std::vector<std::string>> split_sweep_values(const std::string& deck,
                                                                    const std::string& set) {
  const auto eq = set.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == set.size())
    throw DeckError(deck, 0, 0, "", "--set '" + set + "': expected key.path=v1,v2,...");
  std::vector<std::string> values;
  int depth = 0;
  std::string cur;
  for (char c : set.substr(eq + 1)) {
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (c == ',' && depth == 0) {
      values.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  values.push_back(cur);
  for (const std::string& v : values)
    if (v.find_first_not_of(' ') == std::string::npos)
      throw DeckError(deck, 0, 0, set.substr(0, eq), "--set '" + set + "': an empty value");
  return {set.substr(0, eq), values};
}

namespace {
std::string csv_field(const nlohmann::json& j) {
  if (j.is_null()) return "";
  if (j.is_number_float()) return fmt::format("{:.9g}", j.get<double>());
  if (j.is_string()) return j.get<std::string>();
  return j.dump();
}
}  // namespace

int run_sweep(const std::string& deck, const std::vector<std::string>& sets,
              const std::vector<std::string>& fixed, const std::string& out_dir, bool quiet) {
  std::vector<std::pair<std::string, std::vector<std::string>>> axes;
  for (const std::string& s : sets) {
    axes.push_back(split_sweep_values(deck, s));
    const std::string& key = axes.back().first;
    for (std::size_t k = 0; k + 1 < axes.size(); ++k)
      if (axes[k].first == key)
        throw DeckError(deck, 0, 0, key,
                        "swept twice (--set given twice for it); give all its values in one --set");
    if (key == "output.directory")
      throw DeckError(deck, 0, 0, key,
                      "a sweep writes each run into its own run_NNNN folder under --out; it "
                      "cannot be swept");
  }
  std::size_t total = 1;
  for (const auto& a : axes) {
    total *= a.second.size();
    if (total > 10000)
      throw DeckError(deck, 0, 0, a.first, "a sweep of more than 10000 runs; split it");
  }
  // Every combination is validated before the first run starts.
  std::vector<std::vector<std::string>> combos(total);
  std::vector<Deck> decks;
  for (std::size_t k = 0; k < total; ++k) {
    std::size_t rest = k;
    std::vector<std::string> over = fixed;
    for (std::size_t a = axes.size(); a-- > 0;) {
      const auto& vals = axes[a].second;
      combos[k].insert(combos[k].begin(), vals[rest % vals.size()]);
      rest /= vals.size();
    }
    for (std::size_t a = 0; a < axes.size(); ++a) over.push_back(axes[a].first + "=" + combos[k][a]);
    decks.push_back(load_deck(deck, over));
    if (decks.back().solver != Deck::SolverType::Explicit)
      throw DeckError(deck, 0, 0, "solver.type", "sweep runs explicit decks");
  }
  std::filesystem::create_directories(out_dir);
  const OutputFolderLock lock(out_dir);
  std::string head = "run";
  for (const auto& a : axes) head += "," + a.first;
  head += ",status,steps,end_time_s,nodes_final,broken_bonds,damage_sum,crack_initiation_time_s,"
          "crack_branching_time_s,crack_max_speed_m_s,wall_time_s\n";
  std::string csv = head;
  int code = 0;
  install_interrupt_handlers();
  for (std::size_t k = 0; k < total; ++k) {
    const std::string name = fmt::format("run_{:04d}", k);
    RunOptions ro;
    ro.out_dir = out_dir + "/" + name;
    ro.quiet = true;
    if (!quiet) {
      std::string what;
      for (std::size_t a = 0; a < axes.size(); ++a)
        what += fmt::format("{}{}={}", a ? ", " : "", axes[a].first, combos[k][a]);
      fmt::print("sweep {}/{} ({}): {}\n", k + 1, total, name, what);
    }
    RunResult r;
    {
      std::filesystem::create_directories(*ro.out_dir);
      const OutputFolderLock run_lock(*ro.out_dir);
      r = run_simulation(decks[k], ro);
    }
    const nlohmann::json& s = r.summary;
    const nlohmann::json crack = s.contains("crack") ? s["crack"] : nlohmann::json::object();
    auto crack_field = [&](const char* key) {
      return crack.contains(key) ? csv_field(crack[key]) : std::string();
    };
    std::string row = name;
    for (const std::string& v : combos[k]) {
      // A value with commas or quotes is quoted (RFC 4180).
      const bool quote = v.find_first_of(",\"") != std::string::npos;
      std::string q = v;
      if (quote) {
        q.clear();
        for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        q = "\"" + q + "\"";
      }
      row += "," + q;
    }
    row += fmt::format(",{},{},{},{},{},{},{},{},{},{}\n", csv_field(s["status"]),
                       csv_field(s["steps"]), csv_field(s["end_time_s"]),
                       csv_field(s["nodes"]["final"]), csv_field(s["broken_bonds"]),
                       csv_field(s["damage_sum"]), crack_field("initiation_time_s"),
                       crack_field("branching_time_s"), crack_field("max_speed_m_s"),
                       csv_field(s["wall_time_s"]));
    csv += row;
    write_file_atomically(out_dir + "/sweep.csv", [&](std::ostream& o) { o << csv; });
    if (r.interrupted) return 128 + r.interrupted;
    if (r.diverged && code == 0) code = 3;
  }
  if (!quiet) fmt::print("sweep: {} runs, results in {}/sweep.csv\n", total, out_dir);
  return code;
}

}  // namespace periadapt
