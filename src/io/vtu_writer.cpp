#include "io/vtu_writer.hpp"

#include "io/atomic_output.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>

#include <zlib.h>

#include <fmt/format.h>

namespace periadapt {

VtuSeries::VtuSeries(std::string directory, std::string basename, bool zlib)
    : dir_(std::move(directory)), base_(std::move(basename)), compress_(zlib) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw OutputError("cannot create the output folder " + dir_ + ": " + ec.message());
  pvd_ = dir_ + "/" + base_ + ".pvd";
}

std::string VtuSeries::snapshot_stem() const {
  return fmt::format("{}_{:05d}", base_, entries_.size());
}

void VtuSeries::resume(std::vector<std::pair<double, std::string>> entries, bool remove_later) {
  entries_ = std::move(entries);
  if (!remove_later) return;
  // base_NNNNN.vtu, base_NNNNN.pvtu and base_NNNNN_rK.vtu with NNNNN past the series.
  const std::regex name(base_ + R"(_(\d{5,})(\.vtu|\.pvtu|_r\d+\.vtu))");
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir_, ec)) {
    std::smatch m;
    const std::string f = e.path().filename().string();
    if (std::regex_match(f, m, name) && std::stoull(m[1].str()) >= entries_.size())
      std::filesystem::remove(e.path(), ec);
  }
}

std::string VtuSeries::write(double time, const NodeSet& ns, const std::vector<PointField>& fields) {
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) ids.push_back(static_cast<std::uint32_t>(i));
  const std::string name = snapshot_stem() + ".vtu";
  const std::string path = dir_ + "/" + name;
  write_vtu(path, ns, ids, fields);
  entries_.emplace_back(time, name);
  write_pvd();
  return path;
}

std::string VtuSeries::write_piece(double time, const NodeSet& ns, const std::vector<std::uint32_t>& ids,
                                   const std::vector<PointField>& fields, int rank) {
  const std::string path = fmt::format("{}/{}_r{}.vtu", dir_, snapshot_stem(), rank);
  write_vtu(path, ns, ids, fields);
  entries_.emplace_back(time, snapshot_stem() + ".pvtu");
  return path;
}

void VtuSeries::write_parallel_index(const std::vector<PointField>& fields, int pieces) {
  const std::string& name = entries_.back().second;
  const std::string stem = name.substr(0, name.size() - 5);
  write_file_atomically(dir_ + "/" + name, [&](std::ostream& out) {
    out << fmt::format(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
        "byte_order=\"LittleEndian\" header_type=\"UInt64\"{}>\n"
        "  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n",
        compress_ ? " compressor=\"vtkZLibDataCompressor\"" : "");
    for (const PointField& f : fields)
      out << fmt::format(
          "      <PDataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n", f.name,
          f.components);
    out << "    </PPointData>\n    <PPoints>\n"
           "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n    <PCells>\n"
           "      <PDataArray type=\"Int64\" Name=\"connectivity\" NumberOfComponents=\"1\"/>\n"
           "      <PDataArray type=\"Int64\" Name=\"offsets\" NumberOfComponents=\"1\"/>\n"
           "      <PDataArray type=\"UInt8\" Name=\"types\" NumberOfComponents=\"1\"/>\n"
           "    </PCells>\n";
    for (int r = 0; r < pieces; ++r) out << fmt::format("    <Piece Source=\"{}_r{}.vtu\"/>\n", stem, r);
    out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  });
  write_pvd();
}

void VtuSeries::write_vtu(const std::string& path, const NodeSet& ns,
                          const std::vector<std::uint32_t>& ids,
                          const std::vector<PointField>& fields) const {
  const std::uint64_t n = ids.size();
  // Each array's block of the appended section, built first so that the XML header can give
  // their offsets: raw, [uint64 byte count][payload]; zlib, VTK's compressed layout
  // [uint64 blocks][block size][last block's size][compressed size per block][zlib streams].
  std::vector<std::string> blocks;
  auto add_block = [&](const void* p, std::uint64_t bytes) {
    const auto* src = static_cast<const unsigned char*>(p);
    std::string b;
    auto put64 = [&b](std::uint64_t v) { b.append(reinterpret_cast<const char*>(&v), 8); };
    if (!compress_) {
      put64(bytes);
      b.append(reinterpret_cast<const char*>(src), bytes);
    } else {
      constexpr std::uint64_t kBlock = 1 << 16;
      const std::uint64_t nb = (bytes + kBlock - 1) / kBlock;
      put64(nb);
      put64(kBlock);
      put64(nb ? bytes - (nb - 1) * kBlock : 0);
      std::string data;
      std::vector<std::uint64_t> sizes;
      std::vector<unsigned char> z;
      for (std::uint64_t k = 0; k < nb; ++k) {
        const uLong len = static_cast<uLong>(std::min(kBlock, bytes - k * kBlock));
        uLongf zlen = compressBound(len);
        z.resize(zlen);
        if (compress2(z.data(), &zlen, src + k * kBlock, len, Z_DEFAULT_COMPRESSION) != Z_OK)
          throw std::runtime_error("zlib could not compress a VTU array");
        sizes.push_back(zlen);
        data.append(reinterpret_cast<const char*>(z.data()), zlen);
      }
      for (std::uint64_t sz : sizes) put64(sz);
      b += data;
    }
    blocks.push_back(std::move(b));
  };
  std::vector<double> buf;
  for (const PointField& f : fields) {
    buf.resize(n * f.components);
    for (std::uint64_t k = 0; k < n; ++k)
      for (int c = 0; c < f.components; ++c)
        buf[k * f.components + c] = f.data[static_cast<std::size_t>(ids[k]) * f.components + c];
    add_block(buf.data(), buf.size() * 8);
  }
  buf.resize(n * 3);
  for (std::uint64_t k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) buf[k * 3 + d] = ns.x[d][ids[k]];
  add_block(buf.data(), buf.size() * 8);
  std::vector<std::int64_t> ib(n);
  for (std::uint64_t k = 0; k < n; ++k) ib[k] = static_cast<std::int64_t>(k);
  add_block(ib.data(), n * 8);
  for (std::uint64_t k = 0; k < n; ++k) ib[k] = static_cast<std::int64_t>(k + 1);
  add_block(ib.data(), n * 8);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  add_block(types.data(), n);

  // The blocks go into the appended section in the reverse of the tags' order. A reader that
  // walks the blocks in file order and looks each one's tag up by its offset while it rewrites
  // the offsets of the tags done (meshio) then always meets the tag of the block in hand first:
  // in tag order every such rewritten offset could equal a later block's, and did for a third of
  // all node counts.
  std::vector<std::uint64_t> offsets(blocks.size(), 0);
  for (std::size_t k = blocks.size(); k-- > 1;) offsets[k - 1] = offsets[k] + blocks[k].size();
  std::size_t next = 0;
  std::string header;
  auto array_tag = [&](const std::string& type, const std::string& nm, int comps) {
    header += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
        "format=\"appended\" offset=\"{}\"/>\n",
        type, nm, comps, offsets[next++]);
  };
  header += "<?xml version=\"1.0\"?>\n";
  header += fmt::format(
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\"{}>\n  <UnstructuredGrid>\n",
      compress_ ? " compressor=\"vtkZLibDataCompressor\"" : "");
  header += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  header += "      <PointData>\n";
  for (const PointField& f : fields) array_tag("Float64", f.name, f.components);
  header += "      </PointData>\n      <Points>\n";
  array_tag("Float64", "Points", 3);
  header += "      </Points>\n      <Cells>\n";
  array_tag("Int64", "connectivity", 1);
  array_tag("Int64", "offsets", 1);
  array_tag("UInt8", "types", 1);
  header += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
            "  <AppendedData encoding=\"raw\">\n_";
  write_file_atomically(path, [&](std::ostream& out) {
    out << header;
    for (std::size_t k = blocks.size(); k-- > 0;)
      out.write(blocks[k].data(), static_cast<std::streamsize>(blocks[k].size()));
    out << "\n  </AppendedData>\n</VTKFile>\n";
  }, true);
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
