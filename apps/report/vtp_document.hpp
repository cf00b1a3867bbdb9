#pragma once
// A minimal in-memory VTK PolyData piece and its VTK XML (.vtp, ASCII) serialisation:
// the one place that knows the file format; vtp_writer.hpp builds pieces from our types.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace gw {

struct VtpArray {
  std::string name;
  std::string type = "Float64";  // VTK type name: "Float64" or "Int32"
  int components = 1;
  std::vector<double> values;    // tuples flattened; Int32 arrays are written rounded
};

struct VtpPiece {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> lines;  // polylines as point indices
  std::vector<std::vector<int>> polys;  // polygons as point indices
  std::vector<VtpArray> point_data;     // one tuple per point
  std::vector<VtpArray> cell_data;      // one tuple per cell: lines first, then polys (VTK's order)
};

// The piece as a complete VTK XML PolyData document. Throws std::invalid_argument when
// an array's size does not match its point/cell count, an index is out of range, or a
// point is not finite (ASCII VTK readers cannot parse "nan").
std::string vtp_to_xml(const VtpPiece& piece);

}  // namespace gw
