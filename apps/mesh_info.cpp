// mesh-info: load a vessel surface and print its validation report.
//   mesh-info --anatomy anatomies/coronary/coronary.stl [--scale 1000] [--json]
// Exit 0 when the mesh is usable (warnings allowed), 1 with one error line otherwise.
#include <CLI/CLI.hpp>
#include <iostream>

#include "engine/mesh/load_mesh.hpp"
#include "engine/mesh/validate_mesh.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Load a vessel surface mesh (STL/OBJ/PLY) and report its validity"};
  std::string path;
  gw::LoadMeshOptions options;
  bool json = false;
  app.add_option("--anatomy,anatomy", path, "mesh file (.stl, .obj, .ply)")->required();
  app.add_option("--scale", options.scale, "multiply coordinates (1000 for metres -> mm)");
  app.add_flag("--json", json, "print the report as one JSON object");
  CLI11_PARSE(app, argc, argv);

  try {
    gw::MeshReport report;
    gw::load_valid_mesh(path, options, &report);
    if (json)
      std::cout << gw::report_to_json(report) << "\n";
    else
      std::cout << path << "\n" << gw::format_report(report);
    return 0;
  } catch (const gw::MeshError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
