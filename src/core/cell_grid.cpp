#include "core/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace periadapt {

CellGrid::CellGrid(int dim, const std::array<const double*, 3>& coords, std::size_t n,
                   double cell_size)
    : dim_(dim), coords_(coords), h_(cell_size) {
  build(nullptr, n);
}

CellGrid::CellGrid(int dim, const std::array<const double*, 3>& coords,
                   const std::vector<std::uint32_t>& ids, double cell_size)
    : dim_(dim), coords_(coords), h_(cell_size) {
  build(&ids, ids.size());
}

// `n` points: ids[0..n) when given, else 0..n.
void CellGrid::build(const std::vector<std::uint32_t>* ids, std::size_t n) {
  if (!(h_ > 0)) throw std::invalid_argument("CellGrid: cell size must be positive");
  auto id = [&](std::size_t s) { return ids ? (*ids)[s] : static_cast<std::uint32_t>(s); };
  for (int d = 0; d < dim_; ++d) {
    double lo = std::numeric_limits<double>::infinity(), h = -lo;
    for (std::size_t s = 0; s < n; ++s) {
      lo = std::min(lo, coords_[d][id(s)]);
      h = std::max(h, coords_[d][id(s)]);
    }
    if (n == 0) lo = h = 0;
    origin_[d] = lo;
    dims_[d] = std::max<long>(1, static_cast<long>(std::floor((h - lo) / h_)) + 1);
  }
  const std::size_t ncell = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  std::vector<std::uint32_t> cell_of(n);
  start_.assign(ncell + 1, 0);
  for (std::size_t s = 0; s < n; ++s) {
    std::array<long, 3> c{0, 0, 0};
    for (int d = 0; d < dim_; ++d) c[d] = clamp_cell(d, (coords_[d][id(s)] - origin_[d]) / h_);
    cell_of[s] = static_cast<std::uint32_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
    ++start_[cell_of[s] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
  items_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t s = 0; s < n; ++s) items_[fill[cell_of[s]]++] = id(s);
}

}  // namespace periadapt
