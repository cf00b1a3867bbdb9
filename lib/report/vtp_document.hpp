#pragma once
// A minimal in-memory VTK PolyData piece and its VTK XML (.vtp) serialisation, plus the ParaView
// collection (.pvd) that makes a time series of such files: the one place that knows the file
// formats; vtp_writer.hpp builds pieces from our types.
//
// Encoding: VTK XML file version 1.0, little-endian, header_type UInt64, every array "appended" as
// raw binary after the XML (<AppendedData encoding="raw">), each compressed by zlib in blocks of
// 32 KiB with vtkZLibDataCompressor's header [blocks, block size, last block size, compressed size
// of each block] (VTK's own default layout). Read by VTK >= 6 and ParaView, and by our
// read_vtp_polylines (base/graph/vtp_polylines.hpp).
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

// The piece as a complete VTK XML PolyData document (XML header and raw appended binary data, so
// the string holds bytes that are not text). Throws std::invalid_argument when an array's size
// does not match its point/cell count, an index is out of range, or a value is not finite (callers
// drop diverged frames; a NaN point would spoil ParaView's bounds and camera).
std::string vtp_to_xml(const VtpPiece& piece);

// One file of a ParaView collection: the dataset `file` (relative to the .pvd's folder, '/' as the
// separator) at `time_s`; datasets of the same time with different `part` numbers are shown together
// (a multiblock: e.g. part 0 the wire, part 1 the moving wall).
struct PvdEntry {
  double time_s = 0;
  int part = 0;
  std::string file;
};

// The .pvd document (VTKFile type "Collection"): ParaView opens it as one time series (File > Open,
// then the time controls scrub it). Throws std::invalid_argument for a non-finite time, a negative
// part, an empty file name or one with a character XML would need to escape (<, >, &, ", ').
std::string pvd_to_xml(const std::vector<PvdEntry>& entries);

}  // namespace gw
