#pragma once
// Uniform cell list over node positions: O(N) construction, neighbor queries visit the cells that
// overlap a ball. Cells are sorted by id so queries are deterministic.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace periadapt {

class CellGrid {
 public:
  // Builds cells of edge `cell_size` over the given coordinates (arrays of length n, dim used).
  CellGrid(int dim, const std::array<const double*, 3>& coords, std::size_t n, double cell_size);
  // The same over the points `ids` only (ascending; queries report these global ids): a local
  // index for refinement events, whose cost then follows the region, not the model.
  CellGrid(int dim, const std::array<const double*, 3>& coords,
           const std::vector<std::uint32_t>& ids, double cell_size);

  // Calls fn(j) for every point j within distance `radius` of p (squared test, inclusive).
  template <class Fn>
  void for_each_within(const std::array<double, 3>& p, double radius, Fn&& fn) const {
    std::array<long, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int d = 0; d < dim_; ++d) {
      lo[d] = clamp_cell(d, (p[d] - radius - origin_[d]) / h_);
      hi[d] = clamp_cell(d, (p[d] + radius - origin_[d]) / h_);
    }
    const double r2 = radius * radius;
    for (long k = lo[2]; k <= hi[2]; ++k)
      for (long jy = lo[1]; jy <= hi[1]; ++jy)
        for (long ix = lo[0]; ix <= hi[0]; ++ix) {
          std::size_t c = (static_cast<std::size_t>(k) * dims_[1] + jy) * dims_[0] + ix;
          for (std::uint32_t s = start_[c]; s < start_[c + 1]; ++s) {
            std::uint32_t j = items_[s];
            double d2 = 0;
            for (int d = 0; d < dim_; ++d) {
              double t = coords_[d][j] - p[d];
              d2 += t * t;
            }
            if (d2 <= r2) fn(j, d2);
          }
        }
  }

 private:
  void build(const std::vector<std::uint32_t>* ids, std::size_t n);
  long clamp_cell(int d, double c) const {
    long v = static_cast<long>(std::floor(c));
    if (v < 0) v = 0;
    if (v >= dims_[d]) v = dims_[d] - 1;
    return v;
  }
  int dim_;
  std::array<const double*, 3> coords_;
  double h_;
  std::array<double, 3> origin_{0, 0, 0};
  std::array<long, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

}  // namespace periadapt
