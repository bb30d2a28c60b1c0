#include "input/point_cloud.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unordered_map>

namespace periadapt {

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  const auto b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

std::vector<std::array<double, 4>> read_point_cloud(const std::string& path, int dim,
                                                    std::vector<long>* blocks,
                                                    std::vector<long>* lines) {
  if (blocks) blocks->clear();
  if (lines) lines->clear();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw PointCloudError(path + ": cannot open the point file (not a regular file)");
  std::ifstream in(path);
  if (!in) throw PointCloudError(path + ": cannot open the point file");
  const std::vector<std::string> names = dim == 1   ? std::vector<std::string>{"x", "volume"}
                                         : dim == 2 ? std::vector<std::string>{"x", "y", "volume"}
                                                    : std::vector<std::string>{"x", "y", "z", "volume"};
  std::string expected;
  for (const std::string& n : names) expected += (expected.empty() ? "" : ",") + n;
  auto fail = [&](long line, const std::string& what) {
    throw PointCloudError(fmt::format("{}:{}: {}", path, line, what));
  };
  // Lines are read into a fixed buffer: a file without line breaks must not grow a string
  // without bound.
  constexpr std::streamsize kMaxLine = 4096;
  std::vector<char> buf(kMaxLine);
  std::string line;
  long number = 0;
  auto next_line = [&]() {
    if (!in.getline(buf.data(), kMaxLine)) {
      if (in.eof() && in.gcount() == 0) return false;
      if (!in.eof()) fail(number + 1, "a line longer than 4095 characters");
    }
    line.assign(buf.data());
    ++number;
    return true;
  };
  if (!next_line()) fail(1, "empty file; the first line must be the header " + expected);
  std::vector<std::string> header = split(line);
  const bool has_block = !header.empty() && header.back() == "block";
  if (has_block) header.pop_back();
  if (header != names)
    fail(1, "the header must be '" + expected + "' (optionally followed by ',block') for a " +
                std::to_string(dim) + "D model, not '" + trim(line) + "'");
  const std::size_t columns = names.size() + (has_block ? 1 : 0);
  std::vector<std::array<double, 4>> points;
  constexpr std::size_t kMaxPoints = std::size_t{1} << 31;  // node indices are 32-bit
  while (next_line()) {
    if (trim(line).empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != columns)
      fail(number, fmt::format("{} values where the header has {} ({}{})", cells.size(), columns,
                               expected, has_block ? ",block" : ""));
    std::array<double, 4> p{0, 0, 0, 0};
    if (has_block) {
      long b = -1;
      const std::string& cell = cells.back();
      const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), b);
      if (ec != std::errc() || end != cell.data() + cell.size() || b < 0 || b > 2147483647)
        fail(number, "'" + cell + "' in column block is not an integer in 0 ... 2^31 - 1");
      if (blocks) blocks->push_back(b);
    }
    for (std::size_t c = 0; c < names.size(); ++c) {
      double v = 0;
      const auto [end, ec] = std::from_chars(cells[c].data(), cells[c].data() + cells[c].size(), v);
      if (ec != std::errc() || end != cells[c].data() + cells[c].size() || !std::isfinite(v))
        fail(number, "'" + cells[c] + "' in column " + names[c] + " is not a finite number");
      p[c + 1 == names.size() ? 3 : c] = v;
    }
    if (!(p[3] > 0)) fail(number, "the volume must be > 0");
    if (points.size() >= kMaxPoints) fail(number, "more than 2^31 points");
    points.push_back(p);
    if (lines) lines->push_back(number);
  }
  if (points.empty()) fail(number, "no points after the header");
  return points;
}

void check_point_cloud_body(const std::string& path,
                            const std::vector<std::array<double, 4>>& points,
                            const std::vector<long>& lines, int dim, double spacing,
                            double cell_volume) {
  auto line_of = [&](std::size_t k) { return k < lines.size() ? lines[k] : 0L; };
  for (std::size_t k = 0; k < points.size(); ++k)
    if (points[k][3] > 1e3 * cell_volume)
      throw PointCloudError(fmt::format(
          "{}:{}: volume {:g} is more than 1000 cells of the grid spacing ({:g} each); check its "
          "units", path, line_of(k), points[k][3], cell_volume));
  // Near pairs through a hash of cells one spacing wide: each point meets those of its own cell
  // and the neighbouring ones.
  const double tol = 1e-3 * spacing;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  auto key = [&](const std::array<long, 3>& c) {
    return (static_cast<std::uint64_t>(c[0] & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(c[2] & 0x1fffff);
  };
  auto cell_of = [&](const std::array<double, 4>& p) {
    std::array<long, 3> c{0, 0, 0};
    for (int d = 0; d < dim; ++d) c[d] = static_cast<long>(std::floor(p[d] / spacing));
    return c;
  };
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::array<long, 3> c = cell_of(points[k]);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = dim > 1 ? -1 : 0; dy <= (dim > 1 ? 1 : 0); ++dy)
        for (long dz = dim > 2 ? -1 : 0; dz <= (dim > 2 ? 1 : 0); ++dz) {
          const auto it = cells.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == cells.end()) continue;
          for (std::size_t j : it->second) {
            double r2 = 0;
            for (int d = 0; d < dim; ++d) r2 += (points[k][d] - points[j][d]) * (points[k][d] - points[j][d]);
            if (r2 < tol * tol)
              throw PointCloudError(fmt::format(
                  "{}:{}: the point lies {:.3g} m from the point on line {} (less than 1e-3 of the "
                  "spacing {:g} m): a repeated row?",
                  path, line_of(k), std::sqrt(r2), line_of(j), spacing));
          }
        }
    cells[key(c)].push_back(k);
  }
}

}  // namespace periadapt
