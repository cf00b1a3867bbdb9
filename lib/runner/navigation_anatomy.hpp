#pragma once
// From a vessel surface file to what the navigation task needs: the repaired mesh (intake_surface), its wall
// (VesselScene) and its centerline graph — extracted with CGAL MCF through the on-disk cache, or
// read from a given centerline JSON (e.g. an anatomy's ground truth).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "base/mesh/triangle_mesh.hpp"
#include "task/anatomy.hpp"

namespace gw {

struct NavigationAnatomyOptions {
  double scale = 0.0;                     // mesh units -> mm; 0: automatic (metres detected, IntakeOptions)
  std::optional<Eigen::Vector3d> inlet;   // picks the inlet terminal (else the sidecar's, else the widest)
  std::string centerline_path;            // non-empty: use this graph instead of extracting
  bool use_cache = true;
};

struct NavigationAnatomy {
  TriangleMesh mesh;                      // the wall: the file's surface, repaired when it had to be
  std::vector<std::string> repairs;       // what the intake repaired (intake_surface.hpp), one line each
  std::vector<std::string> mesh_warnings; // suspicions it left alone (e.g. maybe centimetres)
  std::string intake_report;              // intake_report_json when anything was repaired or suspected, else ""
  Anatomy anatomy;
  bool centerline_from_cache = false;
  double centerline_seconds = 0.0;        // extraction (or cache read) time
  std::string centerline_source;          // "extracted" | "cache" | the JSON path
  std::string inlet_source;               // "--inlet" | the sidecar truth JSON | "widest end" | the centerline JSON
                                          // | "descending aorta (an aortic arch: femoral access)"
  std::string inlet_warning;              // non-empty when the inlet is a doubtful guess (inlet_ambiguity,
                                          // descending_aorta_inlet's doubtful case)
  std::string inlet_note;                 // how the descending aorta was found, when it was and is no guess
};

// Inlet: options.inlet if set; else the inlet of a ground-truth sidecar STEM.truth.json next to
// the mesh (the committed anatomies have one; it is the insertion point `evaluate` uses, so both
// tools extract and number the same graph); else the widest vessel end, with inlet_warning set
// when another end is nearly as wide; but on an aortic arch (base/graph/descending_aorta_inlet.hpp) the
// descending aorta, the narrower of the aorta's two ends (femoral access), said in inlet_note (inlet_warning
// when the two ends are nearly as wide).
// Throws MeshError / std::runtime_error "<file>: <problem>" for unreadable or invalid meshes and
// for a surface the extraction cannot handle; std::invalid_argument when the graph has no target.
NavigationAnatomy load_navigation_anatomy(const std::string& mesh_path, const NavigationAnatomyOptions& options = {});

// The anatomies a spec names (task/anatomy.hpp: sets, names of `index_path`, or
// mesh paths with a .truth.json beside them), each surface taken in through the mesh intake and
// its graph read from its truth: what guidewire-server trains on. A clean file gives exactly the
// anatomy load_anatomies gives; a user's surface is repaired, with its repairs on stderr. An index entry's
// wire and heart rate (a beating pool's: its own cardiac field at that rate, apply_heart_settings) come with it.
std::vector<Anatomy> load_indexed_anatomies(const std::string& spec, const std::string& index_path);

// "coronary" for ".../coronary.stl".
std::string anatomy_name_from_path(const std::string& mesh_path);

}  // namespace gw
