#include "studies/pdro_disk.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "run/simulation.hpp"
#include "io/line_plot.hpp"
#include "studies/deck_variant.hpp"

namespace periadapt {

namespace {

struct DiskRun {
  std::string name, dir;
  double dx = 0, n = 0;
  std::size_t nodes = 0;
  double wall = 0, damage_sum = 0, checks_per_eval = 0;
  double initiation = NAN, branching = NAN;
  std::set<std::pair<long, long>> cracked;  // pattern cells
  std::vector<double> t, phi;               // damage sum history
};

// time_s and damage_sum columns of a history.csv.
void read_damage_history(const std::string& path, DiskRun& r) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  int ct = -1, cd = -1, c = 0;
  std::stringstream hs(line);
  for (std::string h; std::getline(hs, h, ','); ++c) {
    if (h == "time_s") ct = c;
    if (h == "damage_sum") cd = c;
  }
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string v;
    double t = NAN, p = NAN;
    for (int k = 0; std::getline(ls, v, ','); ++k) {
      if (k == ct) t = std::stod(v);
      if (k == cd) p = std::stod(v);
    }
    r.t.push_back(1e6 * t);
    r.phi.push_back(p);
  }
}

DiskRun run_variant(const PdroDiskOptions& o, const std::string& name, double dx, double n,
                    double cell, const std::string& out_dir) {
  const Deck dk = deck_variant(o.deck, name, [&](YAML::Node& d) {
    d["discretization"]["spacing"] = dx;
    if (n > 0) {
      d["damage"]["overlay"]["n"] = n;
      if (o.pim) d["damage"]["overlay"]["interpolation"] = "pim";
      if (o.gaussian) d["damage"]["overlay"]["weight"] = "gaussian";
      if (o.whole_bond) d["damage"]["overlay"]["sampling"] = "whole_bond";
    }
    d["solver"]["end_time"] = o.snapshot_time;
    d["output"]["vtu_snapshots"] = 1;
    d["output"]["history_every"] = 2;
    d["output"].remove("png_times");  // the end-time picture only
  });
  DiskRun r;
  r.name = name;
  r.dx = dx;
  r.n = n;
  r.dir = fmt::format("{}/disk_dx{:.3f}mm{}", out_dir, 1e3 * dx,
                      n > 0 ? fmt::format("_n{:.2f}", n) : std::string());
  RunOptions ro;
  ro.quiet = true;
  ro.out_dir = r.dir;
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult res = run_simulation(dk, ro);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& s = res.summary;
  r.nodes = s["nodes"]["final"].get<std::size_t>();
  r.damage_sum = s["damage_sum"].get<double>();
  if (s.contains("overlay")) r.checks_per_eval = s["overlay"]["checks_per_bond_evaluation"].get<double>();
  if (s.contains("crack")) {
    if (!s["crack"]["initiation_time_s"].is_null())
      r.initiation = s["crack"]["initiation_time_s"].get<double>();
    if (!s["crack"]["branching_time_s"].is_null())
      r.branching = s["crack"]["branching_time_s"].get<double>();
  }
  const NodeSet& ns = res.model.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && ns.damage(i) > 0.35)
      r.cracked.insert({std::lround(std::floor(ns.x[0][i] / cell)),
                        std::lround(std::floor(ns.x[1][i] / cell))});
  read_damage_history(r.dir + "/history.csv", r);
  return r;
}

}  // namespace

int run_pdro_disk_study(const std::string& out_arg, const PdroDiskOptions& o) {
  const std::string out_dir = out_arg.empty() ? "out/pdro_disk_study" : out_arg;
  std::filesystem::create_directories(out_dir);
  const Deck base = deck_variant(o.deck, "base", [](YAML::Node&) {});
  const double dx = base.grid.spacing, cell = dx;
  const long reach = std::lround(base.horizon / cell);  // pattern tolerance: one coarse horizon
  fmt::print("Stewart & Jeon 2019, 3.3: cooled clamped disk, thermal strain {:.1e}, dx = {:.2f} mm, "
             "m = {:.0f}, G0 = {} J/m^2, to t = {:.0f} us; reference: native dx/2 = {:.3f} mm\n",
             base.thermal_strain, 1e3 * dx, base.horizon_factor, base.G0.value_or(0.0),
             1e6 * o.snapshot_time, 0.5e3 * dx);
  std::vector<DiskRun> runs;
  runs.push_back(run_variant(o, "reference dx/2", 0.5 * dx, 0.0, cell, out_dir));
  runs.push_back(run_variant(o, "plain dx", dx, 0.0, cell, out_dir));
  for (double n : o.overlay_n)
    runs.push_back(run_variant(o, fmt::format("overlay n = {:.1f}", n), dx, n, cell, out_dir));
  const DiskRun& ref = runs[0];
  const DiskRun& plain = runs[1];
  fmt::print("{:<18} {:>7} | {:>8} {:>8} | {:>9} {:>10} {:>7} | {:>8} | {:>7} {:>7} {:>8} | {:>5} "
             "{:>5} {:>7}\n",
             "run", "nodes", "t_i us", "t_b us", "sum phi", "phi*dx mm", "/ref", "pattern", "wall s",
             "/plain", "checks", "cells", "extra", "missing");
  std::vector<PlotSeries> series;
  for (const DiskRun& r : runs) {
    // Cracked cells of either run with no cracked cell of the other within one horizon.
    auto unmatched = [&](const std::set<std::pair<long, long>>& a,
                         const std::set<std::pair<long, long>>& b) {
      std::size_t miss = 0;
      for (const auto& c : a) {
        bool hit = false;
        for (long dxc = -reach; dxc <= reach && !hit; ++dxc)
          for (long dyc = -reach; dyc <= reach && !hit; ++dyc)
            hit = dxc * dxc + dyc * dyc <= reach * reach && b.count({c.first + dxc, c.second + dyc});
        miss += !hit;
      }
      return miss;
    };
    const std::size_t total = r.cracked.size() + ref.cracked.size();
    const std::size_t extra = unmatched(r.cracked, ref.cracked);
    const std::size_t missing = unmatched(ref.cracked, r.cracked);
    const double mismatch =
        total == 0 ? NAN : static_cast<double>(extra + missing) / static_cast<double>(total);
    fmt::print("{:<18} {:>7} | {:>8.2f} {:>8.2f} | {:>9.1f} {:>10.1f} {:>7.3f} | {:>7.1f}% | {:>7.1f} "
               "{:>7.3f} {:>7.4f}% | {:>5} {:>5} {:>7}\n",
               r.name, r.nodes, 1e6 * r.initiation, 1e6 * r.branching, r.damage_sum,
               1e3 * r.damage_sum * r.dx, r.damage_sum * r.dx / (ref.damage_sum * ref.dx),
               100 * mismatch, r.wall,
               &r == &ref ? NAN : r.wall / plain.wall, 100 * r.checks_per_eval, r.cracked.size(),
               extra, missing);
    series.push_back({r.name, r.t, r.phi});
  }
  PlotOptions po;
  po.title = "Total damage vs time (Stewart & Jeon Fig. 9a)";
  po.x_label = "t (us)";
  po.y_label = "sum of node damage";
  write_line_plot(out_dir + "/pdro_disk_damage.png", series, po);
  fmt::print("wrote {0}/pdro_disk_damage.png; damage pictures at the end time in {0}/disk_*/\n",
             out_dir);
  return 0;
}

}  // namespace periadapt
