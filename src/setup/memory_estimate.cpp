#include "setup/memory_estimate.hpp"

#include "material/formulation.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/bond_families.hpp"
#include "core/expression.hpp"
#include "core/node_set.hpp"
#include "input/deck_error.hpp"

namespace periadapt {

namespace {

// MemAvailable of /proc/meminfo (bytes), 0 where it cannot be read.
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return 0;
}

// Extent of the region's bounding box clipped to the body, per dimension (the whole body for
// complements and `all`).
double region_measure(const Shape& s, const Box& body, int dim) {
  Box b = body;
  if (!s.outside) {
    if (s.kind == Shape::Kind::Box) {
      b = s.box;
    } else if (s.kind != Shape::Kind::All) {
      for (int d = 0; d < 3; ++d) {
        const bool along_axis = s.kind == Shape::Kind::Cylinder && d == s.axis;
        b.lo[d] = along_axis ? body.lo[d] : s.center[d] - s.radius;
        b.hi[d] = along_axis ? body.hi[d] : s.center[d] + s.radius;
      }
    }
  }
  double v = 1;
  for (int d = 0; d < dim; ++d) v *= std::max(0.0, std::min(b.hi[d], body.hi[d]) - std::max(b.lo[d], body.lo[d]));
  return v;
}

// Coarse cells the automatic profile refines before the run (adapt/setup_zones.hpp), over-counted:
// every motion's region unless a component is a constant zero velocity or a constant
// displacement, and a ball of two coarse horizons (zone and visibility) per pre-crack end or per
// spacing along a quadrilateral's perimeter.
double setup_zone_cells(const Deck& dk, double nodes) {
  const AdaptSpec& a = dk.adapt;
  const int D = dk.dim;
  const double dx = dk.grid.spacing;
  if (!a.enabled || a.start_time > 0 || !(dx > 0)) return 0;
  double cells = 0;
  if (a.refine_motions)
    for (const MotionSpec& mo : dk.motions) {
      bool fixed = true;
      for (const auto& c : mo.component) {
        if (!c) continue;
        try {
          const Expression ex(*c);
          fixed = fixed && ex.is_constant() &&
                  (mo.kind == MotionSpec::Kind::Displacement || ex(0, 0, 0, 0) == 0.0);
        } catch (const std::exception&) {
          fixed = false;
        }
      }
      if (!fixed) cells += region_measure(mo.region, dk.grid.body, D) / std::pow(dx, D);
    }
  if (a.refine_crack_tips) {
    const double r = dk.horizon;  // the front's visibility ball (not widened again)
    const double ball = D == 3 ? 4.0 / 3.0 * M_PI * r * r * r : D == 2 ? M_PI * r * r : 2 * r;
    for (const PreCrack& c : dk.cracks) {
      double points = 2;
      if (c.planar3d) {
        points = 0;
        for (int k = 0; k < 4; ++k) {
          const Vec3 t = sub(c.points[(k + 1) % 4], c.points[k]);
          points += std::ceil(std::sqrt(dot(t, t)) / dx);
        }
      }
      cells += points * ball / std::pow(dx, D);
    }
  }
  return std::min(cells, nodes);
}

}  // namespace

MemoryEstimate estimate_memory(const Deck& dk) {
  MemoryEstimate e;
  const int D = dk.dim;
  const double dx = dk.grid.spacing;
  const Box& body = dk.grid.body;
  // Nodes of the body's box grid (a rotated lattice covers at most the box's circumscribed one).
  double nodes = 1;
  for (int d = 0; d < D; ++d) {
    double extent = body.hi[d] - body.lo[d];
    if (dk.grid.rotation_deg != 0.0) {
      double diag2 = 0;
      for (int k = 0; k < D; ++k) diag2 += std::pow(body.hi[k] - body.lo[k], 2);
      extent = std::sqrt(diag2);
    }
    nodes *= std::floor(extent / dx) + 2;
  }
  // Initial zones: each coarse node inside becomes 2^(dim level) nodes.
  double added = 0;
  for (const InitialRefinement& z : dk.adapt.initial) {
    const double cells = region_measure(z.region, body, D) / std::pow(dx, D);
    added = std::max(added, std::min(cells, nodes) * (std::pow(2.0, D * z.level) - 1));
  }
  added = std::max(added, setup_zone_cells(dk, nodes) * (std::pow(2.0, D * dk.adapt.max_level) - 1));
  e.nodes = nodes + added;
  // Bonds per node: the horizon ball (widened by half a cell diagonal for the exact-area rules)
  // over the cell measure, at the largest m any level has.
  double m = dk.horizon / dx;
  if (dk.adapt.enabled || !dk.adapt.initial.empty()) {
    const int top = dk.adapt.max_level;
    if (dk.adapt.scaling == HorizonScaling::M) m *= std::pow(2.0, top);
    for (double ml : dk.adapt.m_per_level) m = std::max(m, ml);
  }
  const bool exact_area = dk.quadrature == Quadrature::Subcell || dk.quadrature == Quadrature::IpaHybrid;
  const double r = m + (exact_area ? 0.5 * std::sqrt(static_cast<double>(D)) : 0.0);
  const double per_node = D == 1 ? 2 * r : D == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
  e.bonds = e.nodes * per_node;
  const double spare = dk.adapt.enabled ? 1.25 : 1.0;
  const auto f = Formulation::named(dk.formulation, dk.dual_horizon);
  // Plain LPS across level interfaces: the far ends' quadrature factors, an index per node and
  // at most a float per bond (every row at an interface).
  const bool far_factors = (dk.adapt.enabled || !dk.adapt.initial.empty()) && f &&
                           f->state_based() && !dk.dual_horizon;
  const double per_bond = BondFamilies::bytes_per_bond() +
                          static_cast<double>(f ? f->extra_bytes_per_bond() : 0) +
                          (far_factors ? sizeof(float) : 0);
  e.bytes = e.nodes * (NodeSet::bytes_per_node() + 16 + 24 + (far_factors ? 8 : 0)) +
            e.bonds * per_bond * spare;
  e.available = available_memory();
  return e;
}

void check_memory_estimate(const Deck& dk) {
  const MemoryEstimate e = estimate_memory(dk);
  const std::string what = fmt::format("about {:.3g} nodes and {:.3g} bonds, {:.3g} GB", e.nodes,
                                       e.bonds, e.bytes / 1e9);
  if (!(e.nodes <= 2147483647.0)) {
    // Either the spacing or the body's size can be what is wrong: both are named.
    std::string extent;
    for (int d = 0; d < dk.dim; ++d)
      extent += fmt::format("{}{:.4g}", d ? " x " : "", dk.grid.body.hi[d] - dk.grid.body.lo[d]);
    throw DeckError(dk.file, 0, 0, "discretization.spacing",
                    "the deck asks for " + what + "; at most 2^31 nodes (raise the spacing, or " +
                        fmt::format("check the size of {}{}: its bounding box is {} m at a "
                                    "spacing of {:g} m; lengths are in metres)",
                                    dk.body_at.key,
                                    dk.body_at.line > 0 ? fmt::format(" on line {}", dk.body_at.line)
                                                        : std::string(),
                                    extent, dk.grid.spacing));
  }
  const double limit = dk.memory_limit_gb ? *dk.memory_limit_gb * 1e9 : e.available;
  if (limit > 0 && !(e.bytes <= limit))
    throw DeckError(dk.file, 0, 0,
                    dk.memory_limit_gb ? "solver.memory_limit_gb" : "discretization",
                    fmt::format("the deck asks for {}; {} {:.3g} GB (raise the spacing, lower "
                                "horizon_factor or the refinement levels)",
                                what,
                                dk.memory_limit_gb ? "the deck's limit is"
                                                   : "this machine has available",
                                limit / 1e9));
}

}  // namespace periadapt
