#include "anatomy_gen/write_stl.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace gw {
namespace {

void put_float(std::ofstream& out, double v) {
  const float f = static_cast<float>(v);
  std::array<unsigned char, 4> b;
  std::memcpy(b.data(), &f, 4);  // x86/ARM are little-endian, as STL requires
  out.write(reinterpret_cast<const char*>(b.data()), 4);
}

}  // namespace

void write_stl(const TriangleMesh& mesh, const std::string& path, const std::string& header) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw MeshError(path + ": cannot open for writing");
    std::array<char, 80> head{};
    std::memcpy(head.data(), header.data(), std::min<size_t>(header.size(), 80));
    out.write(head.data(), 80);
    const std::uint32_t n = static_cast<std::uint32_t>(mesh.F.rows());
    const unsigned char count[4] = {static_cast<unsigned char>(n & 0xff), static_cast<unsigned char>((n >> 8) & 0xff),
                                    static_cast<unsigned char>((n >> 16) & 0xff),
                                    static_cast<unsigned char>((n >> 24) & 0xff)};
    out.write(reinterpret_cast<const char*>(count), 4);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
      Eigen::Vector3d normal = (b - a).cross(c - a);
      if (normal.norm() > 0.0) normal.normalize();
      for (int k = 0; k < 3; ++k) put_float(out, normal[k]);
      for (const Eigen::Vector3d* p : {&a, &b, &c})
        for (int k = 0; k < 3; ++k) put_float(out, (*p)[k]);
      const char attribute[2] = {0, 0};
      out.write(attribute, 2);
    }
    if (!out) throw MeshError(path + ": write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw MeshError(path + ": cannot rename temporary file");
}

}  // namespace gw
