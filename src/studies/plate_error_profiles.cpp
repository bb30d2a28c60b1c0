#include "studies/plate_error_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "input/deck_builder.hpp"

namespace periadapt {

namespace {

double mean_over(const std::vector<double>& at, const std::vector<double>& e, double lo, double hi) {
  double s = 0;
  int n = 0;
  for (std::size_t k = 0; k < at.size(); ++k)
    if (at[k] >= lo && at[k] <= hi) s += e[k], ++n;
  return n ? s / n : 0.0;
}

double max_over(const std::vector<double>& at, const std::vector<double>& e, double lo, double hi) {
  double m = 0;
  for (std::size_t k = 0; k < at.size(); ++k)
    if (at[k] >= lo && at[k] <= hi) m = std::max(m, e[k]);
  return m;
}

}  // namespace

double PlateErrors::mean_ex(double lo, double hi) const { return mean_over(x, ex, lo, hi); }
double PlateErrors::max_ex(double lo, double hi) const { return max_over(x, ex, lo, hi); }
double PlateErrors::mean_ey(double lo, double hi) const { return mean_over(y, ey, lo, hi); }
double PlateErrors::max_ey(double lo, double hi) const { return max_over(y, ey, lo, hi); }

Deck tension_plate_deck(const std::string& surface_correction, const std::string& bond_pairing,
                        int refined_level, bool upper_half, const std::string& name) {
  auto box = [](double x0, double y0, double x1, double y1) {
    return DeckBuilder().set("box.min", {x0, y0}).set("box.max", {x1, y1});
  };
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("model.thickness", 0.01)
      .set("material.youngs_modulus", 200.0e9)
      .set("material.density", 7850.0)
      .set("discretization.spacing", 0.01)
      .set("discretization.horizon", 0.03015)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", "ipa_hybrid")
      .set("discretization.surface_correction", surface_correction)
      .set("discretization.body", box(-0.5, -0.25, 0.5, 0.25))
      .append("loads", DeckBuilder()
                           .set("name", "right")
                           .set("type", "traction")
                           .set("region", box(0.5, -0.25, 0.5, 0.25))
                           .set("value", {200.0e6, 0.0}))
      .append("loads", DeckBuilder()
                           .set("name", "left")
                           .set("type", "traction")
                           .set("region", box(-0.5, -0.25, -0.5, 0.25))
                           .set("value", {-200.0e6, 0.0}))
      .append("boundary_conditions",
              DeckBuilder()
                  .set("name", "vertical axis")
                  .set("region", box(0, -0.25, 0, 0.25))
                  .set("displacement", std::vector<std::optional<std::string>>{"0", std::nullopt}))
      .append("boundary_conditions",
              DeckBuilder()
                  .set("name", "horizontal axis")
                  .set("region", box(-0.5, 0, 0.5, 0))
                  .set("displacement", std::vector<std::optional<std::string>>{std::nullopt, "0"}))
      .set("damage.enabled", false)
      .set("solver.type", "static")
      .set("solver.bond_pairing", bond_pairing);
  // The zone stops short of the constrained axis, whose coarse nodes stay.
  if (refined_level > 0)
    d.set("adapt.scaling", "delta")
        .append("adapt.initial_refinement",
                DeckBuilder()
                    .set("region", upper_half ? box(-0.5, 0.001, 0.5, 0.25)
                                              : box(-0.5, -0.25, -0.001, 0.25))
                    .set("level", refined_level));
  return d.build(name);
}

PlateErrors plate_errors(const NodeSet& ns, double p, double E, double nu) {
  PlateErrors r;
  double num = 0, den = 0;
  std::vector<std::pair<double, double>> hx, vy;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double X = ns.x[0][i], Y = ns.x[1][i], h = 0.5 * ns.spacing[i] * (1 + 1e-9);
    const double ux = p * X / E, uy = -nu * p * Y / E;
    num += std::pow(ns.u[0][i] - ux, 2) + std::pow(ns.u[1][i] - uy, 2);
    den += ux * ux + uy * uy;
    const double tiny = 1e-9 * ns.spacing[i];
    if (std::abs(Y) <= h && std::abs(X) > tiny)
      hx.emplace_back(X, 100 * std::abs(ns.u[0][i] - ux) / std::abs(ux));
    if (std::abs(X) <= h && std::abs(Y) > tiny)
      vy.emplace_back(Y, 100 * std::abs(ns.u[1][i] - uy) / std::abs(uy));
  }
  std::sort(hx.begin(), hx.end());
  std::sort(vy.begin(), vy.end());
  for (auto [a, e] : hx) r.x.push_back(a), r.ex.push_back(e);
  for (auto [a, e] : vy) r.y.push_back(a), r.ey.push_back(e);
  r.l2 = den > 0 ? 100 * std::sqrt(num / den) : 0.0;
  return r;
}

}  // namespace periadapt
