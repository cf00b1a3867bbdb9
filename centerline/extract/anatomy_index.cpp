#include "centerline/extract/anatomy_index.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace gw {

std::vector<AnatomyEntry> read_anatomy_index(const std::string& index_path, const std::string& root_in) {
  namespace fs = std::filesystem;
  std::ifstream in(index_path);
  if (!in) throw std::runtime_error(index_path + ": cannot open anatomy index");
  const fs::path root = root_in.empty() ? fs::absolute(index_path).parent_path().parent_path() : fs::path(root_in);
  std::vector<AnatomyEntry> out;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& a : j.at("anatomies")) {
      AnatomyEntry e;
      e.name = a.at("name").get<std::string>();
      e.set = a.value("set", "");
      auto resolve = [&](const char* key) {
        const std::string p = a.value(key, "");
        return p.empty() ? p : (fs::path(p).is_absolute() ? p : (root / p).string());
      };
      e.mesh = resolve("mesh");
      e.truth = resolve("truth");
      e.spec = resolve("spec");
      if (e.mesh.empty() || e.truth.empty() || !fs::exists(e.mesh) || !fs::exists(e.truth)) continue;
      out.push_back(std::move(e));
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(index_path + ": malformed anatomy index (" + e.what() + ")");
  }
  return out;
}

}  // namespace gw
