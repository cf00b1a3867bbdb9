#include "base/mesh/weld_vertices.hpp"

#include <array>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace gw {
namespace {

// Hash of the exact bit pattern: welding is by identity, not by tolerance, so that
// two distinct but close vertices of a fine mesh are never merged by accident.
struct PointKey {
  std::array<double, 3> p;
  bool operator==(const PointKey& o) const { return std::memcmp(p.data(), o.p.data(), sizeof(p)) == 0; }
};
struct PointKeyHash {
  size_t operator()(const PointKey& k) const {
    size_t h = 1469598103934665603ull;
    const auto* bytes = reinterpret_cast<const unsigned char*>(k.p.data());
    for (size_t i = 0; i < sizeof(k.p); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
  }
};

}  // namespace

TriangleMesh weld_vertices(const TriangleMesh& mesh) {
  std::unordered_map<PointKey, int, PointKeyHash> index_of;
  index_of.reserve(static_cast<size_t>(mesh.V.rows()));
  std::vector<std::array<double, 3>> unique;
  unique.reserve(static_cast<size_t>(mesh.V.rows()));
  std::vector<int> remap(static_cast<size_t>(mesh.V.rows()), -1);

  auto weld = [&](int v) {
    if (remap[v] >= 0) return remap[v];
    PointKey key{{mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)}};
    // +0.0 and -0.0 are the same point.
    for (double& c : key.p) if (c == 0.0) c = 0.0;
    auto [it, inserted] = index_of.try_emplace(key, static_cast<int>(unique.size()));
    if (inserted) unique.push_back(key.p);
    remap[v] = it->second;
    return it->second;
  };

  TriangleMesh out;
  out.F.resize(mesh.F.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) out.F(f, c) = weld(mesh.F(f, c));
  out.V.resize(static_cast<Eigen::Index>(unique.size()), 3);
  for (size_t i = 0; i < unique.size(); ++i)
    for (int c = 0; c < 3; ++c) out.V(static_cast<Eigen::Index>(i), c) = unique[i][c];
  return out;
}

}  // namespace gw
