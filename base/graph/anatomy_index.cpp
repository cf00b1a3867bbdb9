#include "base/graph/anatomy_index.hpp"
#include "base/util/read_json_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace gw {

std::vector<AnatomyEntry> read_anatomy_index(const std::string& index_path, const std::string& root_in) {
  namespace fs = std::filesystem;
  const nlohmann::json j = read_json_file(index_path, "anatomy index");
  const nlohmann::json& list = j.is_object() && j.contains("anatomies") ? j["anatomies"] : j;
  if (!list.is_array()) throw std::runtime_error(index_path + ": expected a list of anatomies");
  const fs::path root = root_in.empty() ? fs::absolute(index_path).parent_path().parent_path() : fs::path(root_in);
  std::vector<AnatomyEntry> out;
  for (const auto& a : list) {
    try {
      auto resolve = [&](const char* key, bool required) {
        const std::string p = required ? a.at(key).get<std::string>() : a.value(key, std::string());
        return p.empty() ? p : (fs::path(p).is_absolute() ? p : (root / p).string());
      };
      AnatomyEntry e;
      e.name = a.at("name").get<std::string>();
      e.set = a.value("set", std::string());
      e.mesh = resolve("mesh", true);
      e.truth = resolve("truth", true);
      e.spec = resolve("spec", false);
      e.wire = resolve("wire", false);
      e.heart_rate_bpm = a.value("heart_rate_bpm", 0.0);
      if (!(e.heart_rate_bpm >= 0) || !std::isfinite(e.heart_rate_bpm))
        throw std::runtime_error("'" + e.name + "': heart_rate_bpm must be a number >= 0");
      out.push_back(std::move(e));
    } catch (const std::exception& ex) {
      throw std::runtime_error(index_path + ": bad anatomy entry: " + ex.what());
    }
  }
  return out;
}

}  // namespace gw
