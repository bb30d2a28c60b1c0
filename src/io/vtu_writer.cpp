#include "io/vtu_writer.hpp"

#include "io/atomic_output.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace periadapt {

VtuSeries::VtuSeries(std::string directory, std::string basename)
    : dir_(std::move(directory)), base_(std::move(basename)) {
  std::filesystem::create_directories(dir_);
  pvd_ = dir_ + "/" + base_ + ".pvd";
}

std::string VtuSeries::write(double time, const NodeSet& ns, const std::vector<PointField>& fields) {
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) ids.push_back(static_cast<std::uint32_t>(i));
  const std::uint64_t n = ids.size();
  const std::string name = fmt::format("{}_{:05d}.vtu", base_, entries_.size());
  const std::string path = dir_ + "/" + name;
  write_file_atomically(path, [&](std::ostream& out) {

  // Block layout in the appended section: [uint64 byte count][payload] per array.
  std::uint64_t offset = 0;
  std::string header;
  auto array_tag = [&](const std::string& type, const std::string& nm, int comps,
                       std::uint64_t bytes) {
    header += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
        "format=\"appended\" offset=\"{}\"/>\n",
        type, nm, comps, offset);
    offset += 8 + bytes;
  };
  header += "<?xml version=\"1.0\"?>\n";
  header += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  header += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  header += "      <PointData>\n";
  for (const PointField& f : fields) array_tag("Float64", f.name, f.components, n * f.components * 8);
  header += "      </PointData>\n      <Points>\n";
  array_tag("Float64", "Points", 3, n * 24);
  header += "      </Points>\n      <Cells>\n";
  array_tag("Int64", "connectivity", 1, n * 8);
  array_tag("Int64", "offsets", 1, n * 8);
  array_tag("UInt8", "types", 1, n);
  header += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
            "  <AppendedData encoding=\"raw\">\n_";
  out << header;

  std::vector<double> buf;
  auto put = [&](const void* p, std::uint64_t bytes) {
    out.write(reinterpret_cast<const char*>(&bytes), 8);
    out.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(bytes));
  };
  for (const PointField& f : fields) {
    buf.resize(n * f.components);
    for (std::uint64_t k = 0; k < n; ++k)
      for (int c = 0; c < f.components; ++c)
        buf[k * f.components + c] = f.data[static_cast<std::size_t>(ids[k]) * f.components + c];
    put(buf.data(), buf.size() * 8);
  }
  buf.resize(n * 3);
  for (std::uint64_t k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) buf[k * 3 + d] = ns.x[d][ids[k]];
  put(buf.data(), buf.size() * 8);
  std::vector<std::int64_t> ib(n);
  for (std::uint64_t k = 0; k < n; ++k) ib[k] = static_cast<std::int64_t>(k);
  put(ib.data(), n * 8);
  for (std::uint64_t k = 0; k < n; ++k) ib[k] = static_cast<std::int64_t>(k + 1);
  put(ib.data(), n * 8);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  put(types.data(), n);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  }, true);
  entries_.emplace_back(time, name);
  write_pvd();
  return path;
}

void VtuSeries::write_pvd() const {
  write_file_atomically(pvd_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    for (const auto& [t, f] : entries_)
      out << fmt::format("    <DataSet timestep=\"{:.9e}\" part=\"0\" file=\"{}\"/>\n", t, f);
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace periadapt
