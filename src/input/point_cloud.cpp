#include "input/point_cloud.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

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
                                                    std::vector<long>* blocks) {
  if (blocks) blocks->clear();
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
  }
  if (points.empty()) fail(number, "no points after the header");
  return points;
}

}  // namespace periadapt
