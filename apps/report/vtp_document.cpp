#include "apps/report/vtp_document.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gw {
namespace {

void append_number(std::string& out, double v, bool integer) {
  char buf[32];
  if (integer) std::snprintf(buf, sizeof buf, "%ld", std::lround(v));
  else std::snprintf(buf, sizeof buf, "%.10g", v);  // 10 digits: sub-micrometre at metre scale
  out += buf;
}

void append_array(std::string& out, const VtpArray& a, std::size_t tuples, const char* where) {
  if (a.components < 1) throw std::invalid_argument("VTP array '" + a.name + "' has no components");
  if (a.type != "Float64" && a.type != "Int32")
    throw std::invalid_argument("VTP array '" + a.name + "' has unsupported type '" + a.type + "'");
  if (a.values.size() != tuples * static_cast<std::size_t>(a.components))
    throw std::invalid_argument("VTP " + std::string(where) + " array '" + a.name + "' has " +
                                std::to_string(a.values.size()) + " values, expected " +
                                std::to_string(tuples * static_cast<std::size_t>(a.components)));
  const bool integer = a.type == "Int32";
  out += "        <DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" +
         std::to_string(a.components) + "\" format=\"ascii\">\n          ";
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    const double v = a.values[i];
    // VTK's ASCII reader cannot parse "nan": callers drop non-finite frames, and this
    // check makes a caller's mistake loud instead of writing a file ParaView rejects.
    if (!std::isfinite(v))
      throw std::invalid_argument("VTP " + std::string(where) + " array '" + a.name + "' value " +
                                  std::to_string(i) + " is not finite");
    if (i) out += (i % 9 == 0) ? "\n          " : " ";
    append_number(out, v, integer);
  }
  out += "\n        </DataArray>\n";
}

void append_cells(std::string& out, const char* tag, const std::vector<std::vector<int>>& cells, int npoints) {
  out += "      <" + std::string(tag) + ">\n";
  out += "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n          ";
  std::size_t k = 0;
  for (const auto& c : cells)
    for (int i : c) {
      if (i < 0 || i >= npoints)
        throw std::invalid_argument("VTP " + std::string(tag) + " index " + std::to_string(i) +
                                    " outside 0.." + std::to_string(npoints) + "-1");
      if (k++) out += (k % 12 == 1) ? "\n          " : " ";
      out += std::to_string(i);
    }
  out += "\n        </DataArray>\n";
  out += "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n          ";
  std::size_t offset = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    offset += cells[c].size();
    if (c) out += (c % 12 == 0) ? "\n          " : " ";
    out += std::to_string(offset);
  }
  out += "\n        </DataArray>\n      </" + std::string(tag) + ">\n";
}

}  // namespace

std::string vtp_to_xml(const VtpPiece& p) {
  const std::size_t np = p.points.size();
  const std::size_t nc = p.lines.size() + p.polys.size();
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <PolyData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfVerts=\"0\" NumberOfLines=\"" +
         std::to_string(p.lines.size()) + "\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
         std::to_string(p.polys.size()) + "\">\n";
  out += "      <PointData>\n";
  for (const auto& a : p.point_data) append_array(out, a, np, "point");
  out += "      </PointData>\n      <CellData>\n";
  for (const auto& a : p.cell_data) append_array(out, a, nc, "cell");
  out += "      </CellData>\n";
  VtpArray coords{"Points", "Float64", 3, {}};
  coords.values.reserve(3 * np);
  for (const auto& x : p.points)
    for (int d = 0; d < 3; ++d) coords.values.push_back(x[d]);
  out += "      <Points>\n";
  append_array(out, coords, np, "point");
  out += "      </Points>\n";
  if (!p.lines.empty()) append_cells(out, "Lines", p.lines, static_cast<int>(np));
  if (!p.polys.empty()) append_cells(out, "Polys", p.polys, static_cast<int>(np));
  out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  return out;
}

}  // namespace gw
