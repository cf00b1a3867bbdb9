// anatomy-gen: vessel-tree spec -> watertight STL + ground-truth centerline JSON.
//   anatomy-gen --spec S.json --out DIR [--open-ends] [--deform-phase P]
//   anatomy-gen --regenerate anatomies      (every anatomies/*/*/*.spec.json + index.json)
// Prints one JSON summary line per anatomy; bad specs: "error: FILE: problem", exit 1.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "anatomy_gen/anatomy_set.hpp"
#include "anatomy_gen/generate_anatomy.hpp"
#include "anatomy_gen/tree_spec.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Generate a vessel-tree anatomy (mesh + ground-truth centerline) from a JSON spec"};
  std::string spec_path, out_dir, regenerate_root;
  gw::AnatomyOptions options;
  double phase = -1.0;
  app.add_option("--spec", spec_path, "tree spec (JSON, mm)");
  app.add_option("--out", out_dir, "output folder (created if missing)");
  app.add_flag("--open-ends", options.open_ends, "leave the inlet and outlets open (no caps)");
  app.add_option("--deform-phase", phase, "apply the spec's deformation field at this phase in [0,1]");
  app.add_option("--regenerate", regenerate_root, "regenerate every ROOT/*/*/*.spec.json in place, and ROOT/index.json");
  CLI11_PARSE(app, argc, argv);

  namespace fs = std::filesystem;
  try {
    if (!regenerate_root.empty()) {
      for (const std::string& line : gw::regenerate_anatomy_set(regenerate_root)) std::cout << line << "\n";
      return 0;
    }
    if (spec_path.empty() || out_dir.empty()) {
      std::cerr << "error: give --spec and --out, or --regenerate ROOT\n";
      return 1;
    }
    const gw::TreeSpec spec = gw::read_tree_spec(spec_path);
    if (phase != -1.0) options.deform_phase = phase;
    gw::GeneratedAnatomy anatomy;
    try {
      anatomy = gw::generate_anatomy(spec, options);
    } catch (const std::exception& e) {
      throw gw::SpecError(spec_path + ": " + e.what());
    }
    fs::create_directories(out_dir);
    gw::write_anatomy(anatomy, out_dir);
    // Keep the spec beside its outputs; a phase override is recorded in the copy.
    const fs::path copy = fs::path(out_dir) / (spec.name + ".spec.json");
    if (options.deform_phase) {
      std::ofstream(copy) << gw::tree_spec_to_json(anatomy.spec);
    } else if (!fs::exists(copy) || !fs::equivalent(copy, spec_path)) {
      fs::copy_file(spec_path, copy, fs::copy_options::overwrite_existing);
    }
    std::cout << gw::anatomy_summary_json(anatomy) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
