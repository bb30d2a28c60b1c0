#include "studies/weak_directions.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "studies/study_csv.hpp"

namespace periadapt {

std::vector<double> weak_directions_deg(double m, const std::string& quadrature) {
  // A square patch wide enough that its centre node has a full interior family.
  const int half = static_cast<int>(std::ceil(m)) + 3;
  const double edge = half + 0.5;
  const Model model = build_model(DeckBuilder()
                                      .set("model.dimension", 2)
                                      .set("model.plane", "stress")
                                      .set("material.youngs_modulus", 1.0)
                                      .set("material.density", 1.0)
                                      .set("material.critical_stretch", 0.01)
                                      .set("discretization.spacing", 1.0)
                                      .set("discretization.horizon_factor", m)
                                      .set("discretization.quadrature", quadrature)
                                      .set("discretization.body.box.min", {-edge, -edge})
                                      .set("discretization.body.box.max", {edge, edge})
                                      .set("solver.steps", 1)
                                      .build("weak-directions (built-in)"));
  const NodeSet& ns = model.nodes;
  std::size_t centre = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (std::hypot(ns.x[0][i], ns.x[1][i]) < std::hypot(ns.x[0][centre], ns.x[1][centre])) centre = i;
  std::vector<double> deg;
  const BondFamilies& bf = model.bonds;
  for (std::uint64_t k = bf.begin(centre); k < bf.end(centre); ++k) {
    if (!(bf.beta[k] > 0)) continue;
    const std::size_t j = bf.neighbor[k];
    const double dx = std::abs(ns.x[0][j] - ns.x[0][centre]), dy = std::abs(ns.x[1][j] - ns.x[1][centre]);
    deg.push_back(std::atan2(dy, dx) * 180.0 / M_PI);
  }
  std::sort(deg.begin(), deg.end());
  deg.erase(std::unique(deg.begin(), deg.end(), [](double a, double b) { return b - a < 1e-9; }),
            deg.end());
  return deg;
}

int run_weak_directions_study(const std::string& out_dir) {
  fmt::print("Thesis 5.2: bond (weak) directions of a regular grid in [0, 90] deg, from the family of "
             "an interior node\n(thesis, m = 3: 0, 18.435, 26.565, 30.964, 45, 59.036, 63.435, "
             "71.565, 90; 30.964 and 59.036 are no bond direction of an m = 3 grid)\n");
  std::ofstream csv = open_study_csv(out_dir, "weak_directions.csv",
                                     "m,quadrature,count,directions_deg");
  for (const char* q : {"pa_pdlammps", "ipa_hybrid"})
    for (double m : {2.51, 3.0, 4.0, 5.0, 6.0, 7.0}) {
      const std::vector<double> d = weak_directions_deg(m, q);
      std::string list;
      for (double a : d) list += fmt::format("{}{:.3f}", list.empty() ? "" : " ", a);
      fmt::print("m = {:<4} {:<11} {:>3} directions: {}\n", m, q, d.size(), list);
      if (csv) csv << fmt::format("{},{},{},{}\n", m, q, d.size(), list);
    }
  return 0;
}

}  // namespace periadapt
