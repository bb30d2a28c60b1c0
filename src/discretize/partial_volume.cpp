#include "discretize/partial_volume.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

namespace {

// R^2 - x^2 as (R - x)(R + x): no cancellation near tangency, exactly 0 at |x| = R, and the same
// bits whether or not the compiler contracts a product into an FMA (R * R - x * x did not: 1.9e-8
// of a cell's area at -O2).
double chord2(double R, double x) { return std::max(0.0, (R - std::abs(x)) * (R + std::abs(x))); }

// Antiderivative of sqrt(R^2 - x^2) on [-R, R].
double chord_integral(double x, double R) {
  x = std::clamp(x, -R, R);
  return 0.5 * (x * std::sqrt(chord2(R, x)) + R * R * std::asin(x / R));
}

}  // namespace

double disk_rectangle_area(double x0, double x1, double y0, double y1, double R) {
  // Integrate, over x, the length of [y0, y1] inside the chord [-s(x), s(x)], s = sqrt(R^2-x^2).
  // Between the breakpoints where s(x) = |y0| or |y1| the length is one closed form.
  const double a = std::max(x0, -R), b = std::min(x1, R);
  if (!(b > a) || y1 <= -R || y0 >= R) return 0.0;
  double pts[6] = {a, b, 0, 0, 0, 0};
  int np = 2;
  for (double y : {y0, y1})
    if (std::abs(y) <= R) {  // tangency (|y| = R) splits at x = 0 too
      const double xb = std::sqrt(chord2(R, y));
      for (double c : {-xb, xb})
        if (c > a && c < b) pts[np++] = c;
    }
  // At most six breakpoints: insertion sort (std::sort trips a false -Warray-bounds in GCC 12).
  for (int a = 1; a < np; ++a)
    for (int b = a; b > 0 && pts[b] < pts[b - 1]; --b) std::swap(pts[b], pts[b - 1]);
  double area = 0;
  for (int k = 0; k + 1 < np; ++k) {
    const double l = pts[k], r = pts[k + 1];
    if (!(r > l)) continue;
    const double xm = 0.5 * (l + r);
    const double sm = std::sqrt(chord2(R, xm));
    const bool top_in = y1 <= sm, bottom_in = y0 >= -sm;  // which ends the chord does not clip
    if (std::min(y1, sm) <= std::max(y0, -sm)) continue;  // empty on this piece
    const double S = chord_integral(r, R) - chord_integral(l, R);  // integral of s(x)
    const double w = r - l;
    if (top_in && bottom_in) area += (y1 - y0) * w;
    else if (top_in) area += y1 * w + S;   // from -s(x) to y1
    else if (bottom_in) area += S - y0 * w;  // from y0 to s(x)
    else area += 2 * S;
  }
  return area;
}

double quadrature_search_radius(Quadrature q, int dim, double delta, double dx) {
  if (q != Quadrature::Subcell && q != Quadrature::IpaHybrid) return delta;
  return delta + 0.5 * std::sqrt(static_cast<double>(dim)) * dx;
}

double subcell_fraction(int dim, const std::array<double, 3>& xi, double delta, double dx,
                        double rotation) {
  std::array<double, 3> p = xi;
  if (dim == 2 && rotation != 0.0) {  // into the lattice frame, where cells are axis-aligned
    const double c = std::cos(rotation), s = std::sin(rotation);
    p = {c * xi[0] + s * xi[1], -s * xi[0] + c * xi[1], 0.0};
  }
  double r2 = 0;
  for (int d = 0; d < dim; ++d) r2 += p[d] * p[d];
  const double r = std::sqrt(r2);
  const double half_diag = 0.5 * std::sqrt(static_cast<double>(dim)) * dx;
  if (r + half_diag <= delta) return 1.0;
  if (r - half_diag >= delta) return 0.0;
  if (dim == 1) {  // exact
    const double lo = std::abs(p[0]) - 0.5 * dx;
    return std::clamp((delta - lo) / dx, 0.0, 1.0);
  }
  if (dim == 2) {  // exact analytic area (IPA-Hybrid areas, Seleson 2014)
    const double h = 0.5 * dx;
    return std::clamp(disk_rectangle_area(p[0] - h, p[0] + h, p[1] - h, p[1] + h, delta) / (dx * dx),
                      0.0, 1.0);
  }
  const int n = dim == 2 ? 32 : 12;
  const double h = dx / n, d2 = delta * delta;
  long inside = 0;
  for (int k = 0; k < (dim == 3 ? n : 1); ++k) {
    const double z = dim == 3 ? p[2] - 0.5 * dx + (k + 0.5) * h : 0.0;
    for (int j = 0; j < n; ++j) {
      const double y = p[1] - 0.5 * dx + (j + 0.5) * h;
      for (int i = 0; i < n; ++i) {
        const double x = p[0] - 0.5 * dx + (i + 0.5) * h;
        inside += (x * x + y * y + z * z <= d2);
      }
    }
  }
  return static_cast<double>(inside) / std::pow(static_cast<double>(n), dim);
}

}  // namespace periadapt
