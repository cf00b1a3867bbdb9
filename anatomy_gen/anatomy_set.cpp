#include "anatomy_gen/anatomy_set.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "anatomy_gen/generate_anatomy.hpp"

namespace gw {

namespace fs = std::filesystem;

std::vector<AnatomyEntry> list_anatomy_specs(const std::string& root) {
  if (!fs::is_directory(root)) throw std::runtime_error(root + ": not a directory");
  std::vector<AnatomyEntry> out;
  for (const auto& set : fs::directory_iterator(root)) {
    if (!set.is_directory()) continue;
    for (const auto& anatomy : fs::directory_iterator(set.path())) {
      if (!anatomy.is_directory()) continue;
      const std::string name = anatomy.path().filename().string();
      const fs::path spec = anatomy.path() / (name + ".spec.json");
      if (fs::exists(spec))
        out.push_back({name, set.path().filename().string(), (anatomy.path() / (name + ".stl")).string(),
                       (anatomy.path() / (name + ".truth.json")).string(), spec.string()});
    }
  }
  std::sort(out.begin(), out.end(), [](const AnatomyEntry& a, const AnatomyEntry& b) {
    return std::tie(a.set, a.name) < std::tie(b.set, b.name);
  });
  return out;
}

void write_anatomy_index(const std::string& root) {
  const std::string prefix = fs::path(root).lexically_normal().filename().string().empty()
                                 ? fs::path(root).lexically_normal().parent_path().filename().string()
                                 : fs::path(root).lexically_normal().filename().string();
  nlohmann::json list = nlohmann::json::array();
  for (const AnatomyEntry& e : list_anatomy_specs(root)) {
    const std::string base = prefix + "/" + e.set + "/" + e.name + "/" + e.name;
    list.push_back({{"name", e.name},
                    {"set", e.set},
                    {"mesh", base + ".stl"},
                    {"truth", base + ".truth.json"},
                    {"spec", base + ".spec.json"}});
  }
  const std::string path = (fs::path(root) / "index.json").string();
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << nlohmann::json{{"anatomies", list}}.dump(2) << "\n";
}

std::vector<std::string> regenerate_anatomy_set(const std::string& root) {
  std::vector<std::string> summaries;
  for (const AnatomyEntry& e : list_anatomy_specs(root)) {
    const TreeSpec spec = read_tree_spec(e.spec);
    if (spec.name != e.name) throw SpecError(e.spec + ": name '" + spec.name + "' differs from its folder");
    GeneratedAnatomy a;
    try {
      a = generate_anatomy(spec);
    } catch (const std::exception& ex) {
      throw SpecError(e.spec + ": " + ex.what());
    }
    write_anatomy(a, fs::path(e.spec).parent_path().string());
    summaries.push_back(anatomy_summary_json(a));
  }
  write_anatomy_index(root);
  return summaries;
}

}  // namespace gw
