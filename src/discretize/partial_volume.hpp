#pragma once
// Partial-volume quadrature factors beta for a family node j (cell size dx) seen from a source
// node i with horizon delta.
#include <array>

namespace periadapt {

enum class Quadrature {
  Full,        // beta = 1 for |xi| <= delta (plain one-point rule)
  PaPdlammps,  // PA-PDLAMMPS (thesis 3.1, Fig. 3.1a): linear partial volume, |xi| <= delta only
  Subcell,     // exact covered fraction of the cell by sub-cell sampling; includes cells whose
               // node lies outside the horizon but whose cell is partly inside
};

// The family search radius needed by each rule.
double quadrature_search_radius(Quadrature q, int dim, double delta, double dx);

// PA-PDLAMMPS / full rules (depend on |xi| only).
inline double partial_volume_factor(Quadrature q, double xi, double delta, double dx) {
  if (xi > delta) return 0.0;
  if (q == Quadrature::Full) return 1.0;
  const double inner = delta - 0.5 * dx;
  if (xi <= inner) return 1.0;
  return (delta + 0.5 * dx - xi) / dx;
}

// Fraction of the cell (edge dx, centred at offset xi from the source, lattice rotated by
// `rotation` radians in 2D) inside the ball of radius delta. Cells wholly inside or outside are
// decided exactly; cut cells are sampled on an n^dim sub-grid (error below ~1/n^2 of a cell for
// the smooth boundary; n = 32 in 2D, 12 in 3D).
double subcell_fraction(int dim, const std::array<double, 3>& xi, double delta, double dx,
                        double rotation);

}  // namespace periadapt
