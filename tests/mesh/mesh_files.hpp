#pragma once
// Test helpers: write small meshes in every supported format, and make scratch files.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/mesh/triangle_mesh.hpp"

namespace gw::test {

inline std::string scratch_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "gw_mesh_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// Unit cube [0,1]^3, 8 vertices, 12 outward triangles.
inline TriangleMesh unit_cube() {
  TriangleMesh m;
  m.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3,  // z = 0
      4, 5, 6, 5, 7, 6,     // z = 1
      0, 1, 4, 1, 5, 4,     // y = 0
      2, 6, 3, 3, 6, 7,     // y = 1
      0, 4, 2, 2, 4, 6,     // x = 0
      1, 3, 5, 3, 7, 5;     // x = 1
  return m;
}

inline void write_binary_stl(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = "binary test mesh";
  out.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(m.F.rows());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    float data[12] = {0, 0, 0};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) data[3 + 3 * c + k] = static_cast<float>(m.V(m.F(f, c), k));
    out.write(reinterpret_cast<const char*>(data), sizeof(data));
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

inline void write_ascii_stl(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path);
  out << "solid test\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (int c = 0; c < 3; ++c)
      out << "   vertex " << m.V(m.F(f, c), 0) << " " << m.V(m.F(f, c), 1) << " " << m.V(m.F(f, c), 2) << "\n";
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid test\n";
}

inline void write_obj(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) out << "v " << m.V(v, 0) << " " << m.V(v, 1) << " " << m.V(v, 2) << "\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    out << "f " << m.F(f, 0) + 1 << " " << m.F(f, 1) + 1 << " " << m.F(f, 2) + 1 << "\n";
}

inline void write_ply(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\nelement vertex " << m.V.rows()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.F.rows()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) out << m.V(v, 0) << " " << m.V(v, 1) << " " << m.V(v, 2) << "\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) out << "3 " << m.F(f, 0) << " " << m.F(f, 1) << " " << m.F(f, 2) << "\n";
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace gw::test
