#include "run/resultants.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "core/exact_sum.hpp"
#include "io/csv_column.hpp"
#include "io/line_plot.hpp"
#include "parallel/owned_sums.hpp"

namespace periadapt {

std::string resultant_header(const Model& m) {
  std::string h;
  const char* axes = "xyz";
  auto add = [&](const std::string& base) {
    for (const char* what : {"_f", "_u"})
      for (int d = 0; d < m.nodes.dim; ++d)
        h += fmt::format("{}{}{}_{}", base, what, axes[d], what[1] == 'f' ? "N," : "m,");
  };
  for (const BodyLoad& l : m.loads) add(csv_column_stem("load_", l.name));
  for (const PrescribedMotion& p : m.motions) add(csv_column_stem("bc_", p.name));
  // Impactors: the force each exerts on the body, its position and its velocity.
  for (std::size_t k = 1; k <= m.impactors.size(); ++k)
    for (const char* what : {"_f%_N,", "_%_m,", "_v%_m_s,"})
      for (int d = 0; d < m.nodes.dim; ++d) {
        std::string col = fmt::format("impactor{}{}", k, what);
        col.replace(col.find('%'), 1, 1, axes[d]);
        h += col;
      }
  return h;
}

Vec3 mean_displacement(const NodeSet& ns, const std::vector<std::uint32_t>& nodes,
                       const RowPartition* p) {
  const CountedNodes counted = counted_nodes(p, ns.size());
  std::array<ExactSum, 4> s;  // u V per component, V
  for (std::uint32_t i : nodes) {
    if (!(ns.flags[i] & kActive) || !counted(i)) continue;
    s[3].add(ns.volume[i]);
    for (int d = 0; d < ns.dim; ++d) s[static_cast<std::size_t>(d)].add(ns.u[d][i] * ns.volume[i]);
  }
  add_over_ranks(p, s.data(), s.size());
  const double vol = s[3].value();
  Vec3 u{0, 0, 0};
  for (int d = 0; d < 3; ++d) u[d] = vol > 0 ? s[static_cast<std::size_t>(d)].value() / vol : 0.0;
  return u;
}

std::string resultant_columns(const Model& m,
                              const std::function<Vec3(const BodyLoad&)>& applied,
                              const std::function<Vec3(const PrescribedMotion&)>& reaction,
                              const RowPartition* p) {
  std::string c;
  auto add = [&](const Vec3& F, const Vec3& u) {
    for (int d = 0; d < m.nodes.dim; ++d) c += fmt::format("{:.9e},", F[d]);
    for (int d = 0; d < m.nodes.dim; ++d) c += fmt::format("{:.9e},", u[d]);
  };
  for (const BodyLoad& l : m.loads) add(applied(l), mean_displacement(m.nodes, l.nodes, p));
  for (const PrescribedMotion& pm : m.motions)
    add(reaction(pm), mean_displacement(m.nodes, pm.nodes, p));
  for (const Impactor& im : m.impactors)
    for (const Vec3& v : {scale(im.force, -1.0), im.center, im.velocity})
      for (int d = 0; d < m.nodes.dim; ++d) c += fmt::format("{:.9e},", v[d]);
  return c;
}

nlohmann::json resultants_json(const Model& m,
                               const std::function<Vec3(const BodyLoad&)>& applied,
                               const std::function<Vec3(const PrescribedMotion&)>& reaction) {
  auto vec = [&](const Vec3& v) {
    return std::vector<double>(v.begin(), v.begin() + m.nodes.dim);
  };
  nlohmann::json j = {{"loads", nlohmann::json::object()},
                      {"boundary_conditions", nlohmann::json::object()}};
  for (const BodyLoad& l : m.loads)
    j["loads"][l.name] = {{"force_N", vec(applied(l))},
                          {"mean_displacement_m", vec(mean_displacement(m.nodes, l.nodes))}};
  for (const PrescribedMotion& p : m.motions)
    j["boundary_conditions"][p.name] = {
        {"reaction_N", vec(reaction(p))},
        {"mean_displacement_m", vec(mean_displacement(m.nodes, p.nodes))}};
  return j;
}

Vec3 load_force(const NodeSet& ns, const BodyLoad& load, double amplitude) {
  double volume = 0;
  for (std::uint32_t i : load.nodes)
    if (ns.flags[i] & kActive) volume += ns.volume[i];
  return {amplitude * load.density[0] * volume, amplitude * load.density[1] * volume,
          amplitude * load.density[2] * volume};
}

Vec3 equilibrium_reaction(const Model& m, const PrescribedMotion& pm,
                            const std::array<std::vector<double>, 3>& internal,
                            double load_amplitude_factor) {
  const NodeSet& ns = m.nodes;
  std::vector<char> member(ns.size(), 0);
  for (std::uint32_t i : pm.nodes) member[i] = 1;
  // Body-force densities at the region's nodes (a support may also carry a load).
  std::array<std::vector<double>, 3> body;
  for (auto& b : body) b.assign(ns.size(), 0.0);
  for (const BodyLoad& l : m.loads) {
    const double amp = l.amplitude(1e300) * load_amplitude_factor;
    for (std::uint32_t i : l.nodes)
      if (member[i])
        for (int d = 0; d < ns.dim; ++d) body[d][i] += amp * l.density[d];
  }
  Vec3 R{0, 0, 0};
  for (std::uint32_t i : pm.nodes) {
    if (!(ns.flags[i] & kActive)) continue;
    for (int d = 0; d < ns.dim; ++d)
      if (pm.component[d]) R[d] -= (internal[d][i] + body[d][i]) * ns.volume[i];
  }
  return R;
}

void write_load_displacement_png(const std::string& dir, const std::string& history,
                                 const LoadDisplacementPlot& plot, const Model& m,
                                 bool from_origin) {
  bool is_bc = false;
  for (const PrescribedMotion& p : m.motions) is_bc = is_bc || p.name == plot.name;
  const std::string base = csv_column_stem(is_bc ? "bc_" : "load_", plot.name);
  const char axis = static_cast<char>('x' + plot.component);
  const std::string fcol = fmt::format("{}_f{}_N", base, axis), ucol = fmt::format("{}_u{}_m", base, axis);
  std::istringstream in(history);
  std::string line;
  std::getline(in, line);
  auto split = [](const std::string& l) {
    std::vector<std::string> v;
    std::stringstream ss(l);
    for (std::string c; std::getline(ss, c, ',');) v.push_back(c);
    return v;
  };
  const std::vector<std::string> head = split(line);
  const auto fi = std::find(head.begin(), head.end(), fcol) - head.begin();
  const auto ui = std::find(head.begin(), head.end(), ucol) - head.begin();
  if (fi >= static_cast<long>(head.size()) || ui >= static_cast<long>(head.size())) return;
  PlotSeries ps{plot.name, {}, {}};
  if (from_origin) ps.x.push_back(0.0), ps.y.push_back(0.0);
  while (std::getline(in, line)) {
    const std::vector<std::string> row = split(line);
    if (row.size() != head.size()) continue;
    ps.x.push_back(std::stod(row[static_cast<std::size_t>(ui)]) * 1e3);
    ps.y.push_back(std::stod(row[static_cast<std::size_t>(fi)]));
  }
  PlotOptions po;
  po.title = fmt::format("{}: {} force against mean {} displacement", plot.name,
                         is_bc ? "reaction" : "applied", axis);
  po.x_label = fmt::format("u{} (mm)", axis);
  po.y_label = fmt::format("F{} (N)", axis);
  write_line_plot(dir + "/load_displacement.png", {ps}, po);
}

}  // namespace periadapt
