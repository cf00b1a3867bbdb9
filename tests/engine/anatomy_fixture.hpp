#pragma once
// Loads a committed anatomy (mesh + inlet from its truth JSON) for the contact tests.
#include <Eigen/Core>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "base/mesh/load_mesh.hpp"
#include "engine/scene/vessel_scene.hpp"

namespace gw::test {

struct Anatomy {
  VesselScene scene;
  Eigen::Vector3d inlet, direction;
};

// `name` like "train/t1_straight_y/t1_straight_y" (relative to anatomies/, no extension).
inline Anatomy load_anatomy(const std::string& name) {
  const std::string base = std::string(GW_SOURCE_DIR) + "/anatomies/" + name;
  Anatomy a{make_vessel_scene(load_mesh(base + ".stl")), {}, {}};
  std::ifstream in(base + ".truth.json");
  if (!in) throw std::runtime_error(base + ".truth.json: cannot open");
  nlohmann::json j;
  in >> j;
  for (int i = 0; i < 3; ++i) {
    a.inlet[i] = j["inlet"]["position"][i].get<double>();
    a.direction[i] = j["inlet"]["direction"][i].get<double>();
  }
  a.direction.normalize();
  return a;
}

}  // namespace gw::test
