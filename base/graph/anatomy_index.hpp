#pragma once
// The anatomy index (anatomies/index.json, or a segmentation set's manifest.json): the one reader and
// entry type every library and app uses (the task's anatomy loader, bench-centerline, the generator's
// set writer, the accuracy tests).
#include <string>
#include <vector>

namespace gw {

struct AnatomyEntry {
  std::string name, set;
  std::string mesh, truth, spec;  // paths ("" when the index has none); read_anatomy_index makes them absolute
  std::string wire;               // the wire parameter JSON this anatomy is navigated with ("": the run's wire);
                                  // a pool of aortic arches names the aortic wire (docs/anatomy_pool.md)
  double heart_rate_bpm = 0;      // > 0: its wall beats at this rate with its own cardiac field (a beating pool's)
};

// Reads `index_path`: {"anatomies": [{name, set, mesh, truth, spec, wire, heart_rate_bpm}, ...]} or the bare list
// (spec, wire and heart_rate_bpm optional; a rate must be a number >= 0). Relative
// paths are resolved against `root` (default: the folder above the index's folder, the repository root
// for anatomies/index.json). Files are not checked here (loading one names it when it is missing).
// Throws std::runtime_error "<index_path>: <problem>" for an unreadable or malformed index or an entry
// without a name, mesh or truth.
std::vector<AnatomyEntry> read_anatomy_index(const std::string& index_path, const std::string& root = "");

}  // namespace gw
