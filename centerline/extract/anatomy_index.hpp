#pragma once
// The anatomy set listed in anatomies/index.json: what benchmarks and accuracy tests
// iterate over.
#include <string>
#include <vector>

namespace gw {

struct AnatomyEntry {
  std::string name, set;
  std::string mesh, truth, spec;  // absolute paths (the index holds repo-relative ones)
};

// Reads `index_path` (anatomies/index.json); relative paths in it are resolved against
// `root` (the repository root; default: the folder above the index's folder). Entries
// whose mesh or truth file is missing are skipped. Throws std::runtime_error
// "<index_path>: <problem>" for an unreadable or malformed index.
std::vector<AnatomyEntry> read_anatomy_index(const std::string& index_path, const std::string& root = "");

}  // namespace gw
