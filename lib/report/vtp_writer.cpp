#include "lib/report/vtp_writer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "lib/report/atomic_write.hpp"
#include "lib/report/vtp_document.hpp"

namespace gw {
namespace {

bool finite(const Eigen::Vector3d& p) { return p.allFinite(); }

// Renders and writes a piece; input problems are reported with the output path.
void write_piece(const VtpPiece& piece, const std::string& path) {
  std::string xml;
  try {
    xml = vtp_to_xml(piece);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
  write_file_atomic(path, xml);
}

std::vector<int> append_polyline(VtpPiece& piece, const std::vector<Eigen::Vector3d>& points) {
  std::vector<int> cell;
  for (const auto& p : points) {
    cell.push_back(static_cast<int>(piece.points.size()));
    piece.points.push_back(p);
  }
  return cell;
}

// The frame a wire shape belongs to: recorded, or the last frame when unknown.
int shape_frame(const EpisodeTrace& t, std::size_t shape) {
  if (!t.wire_shape_frame.empty()) return t.wire_shape_frame[shape];
  return static_cast<int>(t.time_s.size()) - 1;  // -1 when there are no frames
}

double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

void write_trace_vtp(const EpisodeTrace& t, const std::string& path) {
  check_trace(t, path);
  VtpPiece piece;
  VtpArray time{"time_s", "Float64", 1, {}}, action{"action", "Float64", 1, {}},
      control{"agent_in_control", "Int32", 1, {}}, frame{"frame", "Int32", 1, {}};
  auto add_frame_data = [&](int f) {
    const bool known = f >= 0;
    const auto i = static_cast<std::size_t>(known ? f : 0);
    time.values.push_back(known ? finite_or_zero(t.time_s[i]) : 0.0);
    action.values.push_back(known ? finite_or_zero(t.action[i]) : 0.0);
    control.values.push_back(known && t.agent_in_control[i] ? 1.0 : 0.0);
    frame.values.push_back(f);
  };
  std::vector<int> tip_cell;
  for (std::size_t i = 0; i < t.tip.size(); ++i) {
    if (!finite(t.tip[i])) continue;  // a diverged frame: nothing to show
    tip_cell.push_back(static_cast<int>(piece.points.size()));
    piece.points.push_back(t.tip[i]);
    add_frame_data(static_cast<int>(i));
  }
  piece.lines.push_back(tip_cell);
  VtpArray kind{"kind", "Int32", 1, {0.0}};
  if (!t.wire_shapes.empty()) {
    const std::size_t last = t.wire_shapes.size() - 1;
    std::vector<int> wire_cell;
    for (const auto& p : t.wire_shapes[last]) {
      if (!finite(p)) continue;
      wire_cell.push_back(static_cast<int>(piece.points.size()));
      piece.points.push_back(p);
      add_frame_data(shape_frame(t, last));
    }
    piece.lines.push_back(wire_cell);
    kind.values.push_back(1.0);
  }
  piece.point_data = {time, action, control, frame};
  piece.cell_data = {kind};
  write_piece(piece, path);
}

void write_wire_shape_vtp(const EpisodeTrace& t, std::size_t shape, const std::string& path) {
  check_trace(t, path);
  if (shape >= t.wire_shapes.size())
    throw std::invalid_argument(path + ": wire shape " + std::to_string(shape) + " of " +
                                std::to_string(t.wire_shapes.size()));
  const int f = t.wire_shape_frame.empty() ? -1 : t.wire_shape_frame[shape];
  VtpPiece piece;
  std::vector<Eigen::Vector3d> tip;
  for (int i = 0; i <= f; ++i)
    if (finite(t.tip[static_cast<std::size_t>(i)])) tip.push_back(t.tip[static_cast<std::size_t>(i)]);
  std::vector<Eigen::Vector3d> wire;
  for (const auto& p : t.wire_shapes[shape])
    if (finite(p)) wire.push_back(p);
  VtpArray arc{"arc_length_mm", "Float64", 1, {}};
  for (const auto* line : {&tip, &wire}) {
    piece.lines.push_back(append_polyline(piece, *line));
    for (std::size_t i = 0; i < line->size(); ++i)
      arc.values.push_back(i == 0 ? 0.0 : arc.values.back() + ((*line)[i] - (*line)[i - 1]).norm());
  }
  const double time = f >= 0 ? finite_or_zero(t.time_s[static_cast<std::size_t>(f)]) : -1.0;
  piece.point_data = {arc};
  piece.cell_data = {{"kind", "Int32", 1, {0.0, 1.0}},
                     {"frame", "Int32", 1, {static_cast<double>(f), static_cast<double>(f)}},
                     {"time_s", "Float64", 1, {time, time}}};
  write_piece(piece, path);
}

std::vector<std::string> write_episode_series(const EpisodeTrace& t, const std::string& pvd_path,
                                              const std::string& folder, const SeriesWall& wall) {
  check_trace(t, pvd_path);
  if (t.wire_shapes.empty()) throw std::invalid_argument(pvd_path + ": the trace has no wire shape to write");
  const std::string dir = std::filesystem::path(pvd_path).parent_path().string();
  auto in_dir = [&](const std::string& relative) {
    return dir.empty() ? relative : (std::filesystem::path(dir) / relative).string();
  };
  std::vector<std::string> written;
  std::vector<PvdEntry> entries;
  for (std::size_t s = 0; s < t.wire_shapes.size(); ++s) {
    const int f = t.wire_shape_frame.empty() ? -1 : t.wire_shape_frame[s];
    const double time = f >= 0 ? finite_or_zero(t.time_s[static_cast<std::size_t>(f)]) : static_cast<double>(s);
    char tag[32];
    std::snprintf(tag, sizeof tag, "%05d", f >= 0 ? f : static_cast<int>(s));
    const std::string wire_file = folder + "/wire_" + tag + ".vtp";
    write_wire_shape_vtp(t, s, in_dir(wire_file));
    written.push_back(in_dir(wire_file));
    entries.push_back({time, 0, wire_file});
    if (wall.file_at) {
      entries.push_back({time, 1, wall.file_at(time)});
    } else if (!wall.static_file.empty()) {
      entries.push_back({time, 1, wall.static_file});
    }
  }
  std::string xml;
  try {
    xml = pvd_to_xml(entries);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(pvd_path + ": " + e.what());
  }
  write_file_atomic(pvd_path, xml);
  written.push_back(pvd_path);
  return written;
}

void write_mesh_vtp(const TriangleMesh& mesh, const std::string& path) {
  if (mesh.V.rows() == 0 || mesh.F.rows() == 0)
    throw std::invalid_argument(path + ": the mesh is empty (" + std::to_string(mesh.V.rows()) + " vertices, " +
                                std::to_string(mesh.F.rows()) + " faces)");
  VtpPiece piece;
  piece.points.reserve(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v).transpose();
    if (!finite(p)) throw std::invalid_argument(path + ": mesh vertex " + std::to_string(v) + " is not finite");
    piece.points.push_back(p);
  }
  piece.polys.reserve(static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) piece.polys.push_back({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)});
  write_piece(piece, path);
}

void write_polyline_vtp(const std::vector<Eigen::Vector3d>& points, const std::string& path,
                        const std::vector<double>& radius) {
  if (points.empty()) throw std::invalid_argument(path + ": the polyline has no points");
  if (!radius.empty() && radius.size() != points.size())
    throw std::invalid_argument(path + ": " + std::to_string(radius.size()) + " radii for " +
                                std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) throw std::invalid_argument(path + ": polyline point " + std::to_string(i) + " is not finite");
  VtpPiece piece;
  piece.lines.push_back(append_polyline(piece, points));
  VtpArray arc{"arc_length_mm", "Float64", 1, {0.0}};
  for (std::size_t i = 1; i < points.size(); ++i) arc.values.push_back(arc.values.back() + (points[i] - points[i - 1]).norm());
  piece.point_data.push_back(arc);
  if (!radius.empty()) piece.point_data.push_back({"radius_mm", "Float64", 1, radius});
  write_piece(piece, path);
}

void write_centerline_vtp(const CenterlineGraph& graph, const std::string& path) {
  if (graph.branches.empty()) throw std::invalid_argument(path + ": the centerline graph has no branch");
  VtpPiece piece;
  VtpArray radius{"radius_mm", "Float64", 1, {}}, branch{"branch", "Int32", 1, {}}, parent{"parent", "Int32", 1, {}};
  for (const auto& b : graph.branches) {
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      if (!finite(b.points[i]))
        throw std::invalid_argument(path + ": branch " + std::to_string(b.id) + " point " + std::to_string(i) +
                                    " is not finite");
      // A graph without radii (or with a partial list) still draws; radius 0 says "unknown".
      radius.values.push_back(i < b.radii.size() ? finite_or_zero(b.radii[i]) : 0.0);
    }
    piece.lines.push_back(append_polyline(piece, b.points));
    branch.values.push_back(b.id);
    parent.values.push_back(b.parent);
  }
  piece.point_data = {radius};
  piece.cell_data = {branch, parent};
  write_piece(piece, path);
}

}  // namespace gw
