#include "lib/report/vtp_document.hpp"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace gw {
namespace {

constexpr std::size_t kBlockBytes = 32768;  // VTK's default compressor block size

void put_u64(std::string& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));  // little-endian
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

// vtkZLibDataCompressor's layout with a UInt64 header: [blocks, block size, last block size (0 when
// the last block is full), compressed size of each block], then the compressed blocks.
std::string compress_blocks(const std::string& raw) {
  const std::size_t blocks = (raw.size() + kBlockBytes - 1) / kBlockBytes;
  std::vector<std::string> packed(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = b * kBlockBytes, n = std::min(kBlockBytes, raw.size() - begin);
    uLongf length = compressBound(static_cast<uLong>(n));
    packed[b].resize(length);
    const int rc = compress2(reinterpret_cast<Bytef*>(packed[b].data()), &length,
                             reinterpret_cast<const Bytef*>(raw.data() + begin), static_cast<uLong>(n),
                             Z_DEFAULT_COMPRESSION);
    if (rc != Z_OK) throw std::runtime_error("zlib compress2 failed (" + std::to_string(rc) + ")");
    packed[b].resize(length);
  }
  std::string out;
  put_u64(out, blocks);
  put_u64(out, kBlockBytes);
  put_u64(out, raw.size() % kBlockBytes);
  for (const auto& p : packed) put_u64(out, p.size());
  for (const auto& p : packed) out += p;
  return out;
}

// Collects the appended section and writes each array's XML element pointing into it.
struct Appended {
  std::string data;

  void add(std::string& xml, const std::string& indent, const std::string& attributes, const std::string& raw) {
    xml += indent + "<DataArray " + attributes + " format=\"appended\" offset=\"" + std::to_string(data.size()) +
           "\"/>\n";
    data += compress_blocks(raw);
  }
};

std::string array_bytes(const VtpArray& a, const char* where) {
  std::string raw;
  const bool integer = a.type == "Int32";
  raw.reserve(a.values.size() * (integer ? 4 : 8));
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    const double v = a.values[i];
    if (!std::isfinite(v))
      throw std::invalid_argument("VTP " + std::string(where) + " array '" + a.name + "' value " + std::to_string(i) +
                                  " is not finite");
    if (integer) {
      put_u32(raw, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(v))));
    } else {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      put_u64(raw, bits);
    }
  }
  return raw;
}

void append_array(std::string& xml, Appended& app, const VtpArray& a, std::size_t tuples, const char* where) {
  if (a.components < 1) throw std::invalid_argument("VTP array '" + a.name + "' has no components");
  if (a.type != "Float64" && a.type != "Int32")
    throw std::invalid_argument("VTP array '" + a.name + "' has unsupported type '" + a.type + "'");
  if (a.values.size() != tuples * static_cast<std::size_t>(a.components))
    throw std::invalid_argument("VTP " + std::string(where) + " array '" + a.name + "' has " +
                                std::to_string(a.values.size()) + " values, expected " +
                                std::to_string(tuples * static_cast<std::size_t>(a.components)));
  app.add(xml, "        ",
          "type=\"" + a.type + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" + std::to_string(a.components) + "\"",
          array_bytes(a, where));
}

void append_cells(std::string& xml, Appended& app, const char* tag, const std::vector<std::vector<int>>& cells,
                  int npoints) {
  VtpArray connectivity{"connectivity", "Int32", 1, {}}, offsets{"offsets", "Int32", 1, {}};
  for (const auto& c : cells) {
    for (int i : c) {
      if (i < 0 || i >= npoints)
        throw std::invalid_argument("VTP " + std::string(tag) + " index " + std::to_string(i) + " outside 0.." +
                                    std::to_string(npoints) + "-1");
      connectivity.values.push_back(i);
    }
    offsets.values.push_back(static_cast<double>(connectivity.values.size()));
  }
  xml += "      <" + std::string(tag) + ">\n";
  app.add(xml, "        ", "type=\"Int32\" Name=\"connectivity\"", array_bytes(connectivity, tag));
  app.add(xml, "        ", "type=\"Int32\" Name=\"offsets\"", array_bytes(offsets, tag));
  xml += "      </" + std::string(tag) + ">\n";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

std::string vtp_to_xml(const VtpPiece& p) {
  const std::size_t np = p.points.size();
  const std::size_t nc = p.lines.size() + p.polys.size();
  Appended app;
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
         "compressor=\"vtkZLibDataCompressor\">\n";
  out += "  <PolyData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfVerts=\"0\" NumberOfLines=\"" +
         std::to_string(p.lines.size()) + "\" NumberOfStrips=\"0\" NumberOfPolys=\"" + std::to_string(p.polys.size()) +
         "\">\n";
  out += "      <PointData>\n";
  for (const auto& a : p.point_data) append_array(out, app, a, np, "point");
  out += "      </PointData>\n      <CellData>\n";
  for (const auto& a : p.cell_data) append_array(out, app, a, nc, "cell");
  out += "      </CellData>\n";
  VtpArray coords{"Points", "Float64", 3, {}};
  coords.values.reserve(3 * np);
  for (const auto& x : p.points)
    for (int d = 0; d < 3; ++d) coords.values.push_back(x[d]);
  out += "      <Points>\n";
  append_array(out, app, coords, np, "point");
  out += "      </Points>\n";
  if (!p.lines.empty()) append_cells(out, app, "Lines", p.lines, static_cast<int>(np));
  if (!p.polys.empty()) append_cells(out, app, "Polys", p.polys, static_cast<int>(np));
  out += "    </Piece>\n  </PolyData>\n";
  out += "  <AppendedData encoding=\"raw\">\n   _";
  out += app.data;
  out += "\n  </AppendedData>\n</VTKFile>\n";
  return out;
}

std::string pvd_to_xml(const std::vector<PvdEntry>& entries) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const PvdEntry& e : entries) {
    if (!std::isfinite(e.time_s)) throw std::invalid_argument("PVD dataset '" + e.file + "' has a non-finite time");
    if (e.part < 0) throw std::invalid_argument("PVD dataset '" + e.file + "' has a negative part");
    if (e.file.empty() || e.file.find_first_of("<>&\"'") != std::string::npos)
      throw std::invalid_argument("PVD dataset file name '" + e.file + "' is empty or needs XML escaping");
    out += "    <DataSet timestep=\"" + number(e.time_s) + "\" group=\"\" part=\"" + std::to_string(e.part) +
           "\" file=\"" + e.file + "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

}  // namespace gw
