#pragma once
// A body given as a point cloud (discretization.body.points): a CSV file with the header
// "x,volume" (1D), "x,y,volume" (2D) or "x,y,z,volume" (3D) and one node per row, for users who
// make their own nodes. The nodes keep the deck's grid spacing (quadrature and refinement assume
// lattice cells), their coordinates and volumes are taken as written (shortest round-trip
// decimals reproduce a lattice bit for bit: `periadapt check DECK --write-nodes FILE`).
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace periadapt {

struct PointCloudError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// (x, y, z, volume) per row; throws PointCloudError naming the file and line. The header may end
// with a "block" column (a non-negative integer per row: named node sets, as Peridigm's text
// discretization has); `blocks` receives it (empty without the column), `lines` (optional) each
// point's line number.
std::vector<std::array<double, 4>> read_point_cloud(const std::string& path, int dim,
                                                    std::vector<long>* blocks = nullptr,
                                                    std::vector<long>* lines = nullptr);

// Points a body cannot be made of: two closer than 1e-3 of the grid spacing (a duplicated row:
// a bond of length ~0 and a stable step ~0), or a volume above 1000 cells of the spacing (a
// typo: its mass would outweigh every family it joins). Throws PointCloudError naming the file
// and the lines.
void check_point_cloud_body(const std::string& path,
                            const std::vector<std::array<double, 4>>& points,
                            const std::vector<long>& lines, int dim, double spacing,
                            double cell_volume);

}  // namespace periadapt
