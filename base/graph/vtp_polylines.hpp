#pragma once
// The polylines of a VTK XML PolyData file (.vtp), as vtkXMLPolyDataWriter writes them (what
// vmtkcenterlines and 3D Slicer save). For read_vmtk_centerline.
// In:  a path; the names of the one-component point arrays wanted.
// Out: points (double), one id list per line cell (polylines; vertices, strips and polygons are
//      ignored), the wanted arrays per point, and the field-data string "SPACE" ("LPS"/"RAS",
//      as 3D Slicer tags the files it writes; "" when absent).
// Encodings: ascii, binary (inline base64) and appended (raw or base64), each uncompressed or
// zlib-compressed (vtkZLibDataCompressor), header_type UInt32/UInt64, either byte order,
// Float32/Float64 and (U)Int8..64 arrays. XML through pugixml, inflate through zlib.
// A bad file throws std::runtime_error "<path>: <problem>" (missing array, wrong type or size,
// bad base64, truncated or corrupt zlib data, offsets out of range, no lines); it never crashes.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace gw {

struct VtpPolylines {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::int64_t>> lines;             // point ids of each polyline cell
  std::map<std::string, std::vector<double>> point_arrays;  // the requested arrays, one value per point
  std::string space;                                        // field data "SPACE": "LPS", "RAS" or ""
};

VtpPolylines read_vtp_polylines(const std::string& path, const std::vector<std::string>& point_arrays);

}  // namespace gw
