#pragma once
// Partial-volume quadrature factors beta for a family node j (cell size dx) seen from a source
// node i with horizon delta.
#include <array>

namespace periadapt {

enum class Quadrature {
  Full,        // beta = 1 for |xi| <= delta (plain one-point rule)
  PaPdlammps,  // PA-PDLAMMPS (thesis 3.1, Fig. 3.1a): linear partial volume, |xi| <= delta only
  Subcell,     // covered fraction of the cell: exact in 1D and 2D, sub-cell sampling in 3D;
               // includes cells whose node lies outside the horizon but whose cell is partly in
  IpaHybrid,   // 2D: the analytic covered areas of Seleson's IPA algorithms (thesis 3.1,
               // Fig. 3.1b), quadrature point at the node (same factors as Subcell in 2D)
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

// Area of the rectangle [x0, x1] x [y0, y1] inside the disk of radius R centred at the origin.
double disk_rectangle_area(double x0, double x1, double y0, double y1, double R);

// Fraction of the cell (edge dx, centred at offset xi from the source, lattice rotated by
// `rotation` radians in 2D) inside the ball of radius delta. Exact in 1D and 2D (analytic
// area); in 3D cut cells are sampled on a 12^3 sub-grid (error below ~1% of a cut cell).
double subcell_fraction(int dim, const std::array<double, 3>& xi, double delta, double dx,
                        double rotation);

}  // namespace periadapt
