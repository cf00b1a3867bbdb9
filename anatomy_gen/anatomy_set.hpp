#pragma once
// The committed anatomy set: ROOT/<set>/<name>/<name>.{spec.json,stl,truth.json} and
// ROOT/index.json listing every anatomy with repository-relative paths.
#include <string>
#include <vector>

#include "base/graph/anatomy_index.hpp"

namespace gw {

// Every ROOT/*/*/*.spec.json whose file name matches its folder, sorted by set then name: entries with
// `spec` and the mesh and truth paths the generator writes beside it.
std::vector<AnatomyEntry> list_anatomy_specs(const std::string& root);

// Writes ROOT/index.json: {"anatomies": [{name, set, mesh, truth, spec}, ...]} with paths
// prefixed by ROOT's folder name (e.g. "anatomies/train/t1/t1.stl").
void write_anatomy_index(const std::string& root);

// Regenerates every listed anatomy in place (mesh + truth, capped) and the index.
// Returns one summary JSON line per anatomy. Throws on the first failing spec, naming it.
std::vector<std::string> regenerate_anatomy_set(const std::string& root);

}  // namespace gw
