#include "anatomy_gen/generate_anatomy.hpp"

#include <chrono>
#include <nlohmann/json.hpp>

#include "anatomy_gen/deformation.hpp"
#include "anatomy_gen/mesh_tree_surface.hpp"
#include "anatomy_gen/open_ends.hpp"
#include "anatomy_gen/tree_geometry.hpp"
#include "anatomy_gen/truth_graph.hpp"
#include "anatomy_gen/tube_field.hpp"
#include "anatomy_gen/write_stl.hpp"
#include "base/mesh/validate_mesh.hpp"

namespace gw {

GeneratedAnatomy generate_anatomy(const TreeSpec& spec, const AnatomyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  GeneratedAnatomy out;
  out.spec = spec;
  TreeSpec shaped = spec;
  if (options.deform_phase) {
    const double phase = *options.deform_phase;
    if (!(phase >= 0.0 && phase <= 1.0)) throw SpecError("deformation phase must be in [0,1]");
    if (!spec.deformation.present) throw SpecError("a deformation phase was given but the spec has no deformation field");
    out.spec.deformation.phase = phase;
  }
  if (out.spec.deformation.present && out.spec.deformation.phase > 0.0)
    shaped = deform_spec(spec, out.spec.deformation, out.spec.deformation.phase);

  const TreeGeometry geometry = build_tree_geometry(shaped);
  const TubeField field(geometry);
  out.mesh = mesh_tree_surface(geometry, field);
  const MeshReport report = validate_mesh(out.mesh);
  if (!report.closed() || !report.manifold() || report.components != 1 || report.volume <= 0.0)
    throw MeshError(spec.name + ": generated surface failed its checks (boundary edges " +
                    std::to_string(report.boundary_edges) + ", non-manifold edges " +
                    std::to_string(report.non_manifold_edges) + ", components " + std::to_string(report.components) +
                    ")");
  out.volume = report.volume;
  if (options.open_ends) out.mesh = remove_end_caps(out.mesh, geometry.caps);
  out.truth = build_truth_graph(geometry);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void write_anatomy(const GeneratedAnatomy& a, const std::string& dir) {
  write_stl(a.mesh, dir + "/" + a.spec.name + ".stl", "guidewire-nav anatomy " + a.spec.name + " (mm)");
  write_centerline(a.truth, dir + "/" + a.spec.name + ".truth.json");
}

std::string anatomy_summary_json(const GeneratedAnatomy& a) {
  nlohmann::json j;
  j["name"] = a.spec.name;
  j["faces"] = a.mesh.F.rows();
  j["vertices"] = a.mesh.V.rows();
  j["volume_mm3"] = a.volume;
  j["targets"] = a.truth.targets.size();
  j["bifurcations"] = a.truth.bifurcations.size();
  j["seconds"] = a.seconds;
  return j.dump();
}

}  // namespace gw
