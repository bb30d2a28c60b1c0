// Deck section output.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "io/csv_column.hpp"
#include "input/yaml_section.hpp"

namespace periadapt::deck_sections {

void parse_output(Section& top, Deck& dk) {
  // --- output
  if (auto o = top.optional_section("output")) {
    OutputSpec& out = dk.output;
    out.directory = o->text("directory", out.directory);
    if (out.directory.empty()) o->fail("directory", "must name a folder (for the current one: '.')");
    out.vtu = o->boolean("vtu", true);
    out.stress = o->boolean("stress", false);
    out.vtu_zlib = o->choice("vtu_compression", {"none", "zlib"}, "none") == "zlib";
    for (Section r : o->list("regions")) {
      NamedRegion nr;
      nr.name = r.text("name");
      if (nr.name.empty()) r.fail("name", "must not be empty");
      for (const NamedRegion& other : out.regions)
        if (csv_column_stem("", other.name) == csv_column_stem("", nr.name))
          r.fail("name", other.name == nr.name
                             ? "'" + nr.name + "' names two output regions"
                             : "'" + nr.name + "' and the output region '" + other.name +
                                   "' give the same history.csv columns (region_" +
                                   csv_column_stem("", nr.name) +
                                   "_...: characters other than letters and digits become '_'); "
                                   "rename one");
      nr.region = parse_region(r.section("region"), dk.dim);
      r.finish();
      out.regions.push_back(std::move(nr));
    }
    out.vtu_count = static_cast<int>(o->integer("vtu_snapshots", 10, [](long v) {
      return (v >= 0 && v <= 100000) ? std::string() : std::string("must be in 0 ... 100000");
    }));
    out.history_every = o->integer("history_every", 10, [](long v) {
      return v >= 1 ? std::string() : std::string("must be >= 1");
    });
    out.checkpoint_every = o->integer("checkpoint_every", 0, [](long v) {
      return v >= 0 ? std::string() : std::string("must be >= 0 (0: no periodic checkpoints)");
    });
    if (o->has("png_times")) out.png_times = o->numbers("png_times", 1, 1000);
    out.png_width = static_cast<int>(o->integer("png_width", 1200, [](long v) {
      return (v >= 100 && v <= 8000) ? std::string() : std::string("must be in [100, 8000]");
    }));
    if (auto ld = o->optional_section("load_displacement")) {
      LoadDisplacementPlot p;
      p.name = ld->text("name");
      bool known = false;
      std::string names;
      for (const LoadSpec& l : dk.loads) known = known || l.name == p.name, names += " " + l.name;
      for (const MotionSpec& mo : dk.motions)
        known = known || mo.name == p.name, names += " " + mo.name;
      if (!known)
        ld->fail("name", "'" + p.name + "' names no load or boundary condition; the names are:" +
                             (names.empty() ? std::string(" (none)") : names));
      const std::string c = ld->choice("component", dk.dim == 1   ? std::vector<std::string>{"x"}
                                                    : dk.dim == 2 ? std::vector<std::string>{"x", "y"}
                                                                  : std::vector<std::string>{"x", "y", "z"},
                                       "x");
      p.component = c[0] - 'x';
      ld->finish();
      out.load_displacement = p;
    }
    if (auto ct = o->optional_section("crack_tip")) {
      out.track_tip = true;
      out.tip_threshold = ct->number("threshold", 0.35, in_range(0, 1));
      if (ct->has("origin"))
        out.tip_origin = to_vec(ct->numbers("origin", static_cast<std::size_t>(dk.dim),
                                            static_cast<std::size_t>(dk.dim)));
      if (ct->has("direction")) {
        Vec3 d = to_vec(ct->numbers("direction", static_cast<std::size_t>(dk.dim),
                                    static_cast<std::size_t>(dk.dim)));
        if (norm(d) <= 0) ct->fail("direction", "must be a non-zero vector");
        out.tip_direction = scale(d, 1.0 / norm(d));
      }
      out.tip_side = ct->choice("side", {"both", "upper", "lower"}, "both");
      out.tip_window = ct->number("speed_window", 2e-6, positive());
      if (ct->has("advance")) out.tip_advance = ct->number("advance", std::nullopt, positive());
      if (ct->has("branch_gap")) out.branch_gap = ct->number("branch_gap", std::nullopt, positive());
      ct->finish();
    }
    o->finish();
  }
  if (!dk.output.track_tip && !dk.cracks.empty() && dk.dim == 2) dk.output.track_tip = true;
}

}  // namespace periadapt::deck_sections
