// mesh-info: load a vessel surface, print its validation report and what the intake repairs.
//   mesh-info --anatomy anatomies/coronary/coronary.stl [--scale 1000] [--json] [--out repaired.stl]
// Exit 0 when the mesh is usable after repair, 1 with one error line otherwise.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "centerline/intake_surface.hpp"
#include "anatomy_gen/write_stl.hpp"
#include "base/mesh/validate_mesh.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Load a vessel surface mesh (STL/OBJ/PLY), report its validity and the repairs it gets"};
  std::string path;
  gw::IntakeOptions options;
  bool json = false;
  std::string out;
  app.add_option("--anatomy,anatomy", path, "mesh file (.stl, .obj, .ply)")->required();
  app.add_option("--scale", options.scale, "multiply coordinates (1000 for metres -> mm); default: automatic");
  app.add_flag("--json", json, "print the report as one JSON object {\"mesh\": ..., \"intake\": ...}");
  app.add_option("--out", out, "write the repaired closed surface (what the centerline is extracted from) as binary STL, mm");
  CLI11_PARSE(app, argc, argv);

  try {
    if (app.count("--scale") && (!(options.scale > 0) || !std::isfinite(options.scale)))
      throw gw::MeshError(path + ": --scale must be a positive number");
    const gw::IntakeSurface s = gw::intake_surface(path, options);
    if (!out.empty()) gw::write_stl(s.closed.mesh, out, "guidewire-nav mesh-info: repaired surface of " + path);
    if (json) {
      nlohmann::json j = {{"mesh", nlohmann::json::parse(gw::report_to_json(s.input))},
                          {"intake", nlohmann::json::parse(gw::intake_report_json(s))}};
      std::cout << j.dump() << "\n";
    } else {
      std::cout << path << "\n" << gw::format_report(s.input);
      if (s.repairs.empty()) std::cout << "intake: used as it is (closed, one piece, outward)\n";
    }
    // As every app prints them: on stderr, naming the file (the --json report holds them too).
    for (const std::string& r : s.repairs) std::cerr << "repaired: " << path << ": " << r << "\n";
    for (const std::string& w : s.warnings) std::cerr << "warning: " << path << ": " << w << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
