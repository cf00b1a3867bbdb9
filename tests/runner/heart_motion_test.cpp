// The beating heart's settings (issue 36 item 4, lib/runner/heart_motion.hpp): which cardiac motion an
// anatomy gets, that 0 bpm changes nothing, a motion frozen in a deformed shape takes the centerline with
// it, and evaluate's beating rows (item 5) come after the paper's rows, which stay as they were.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "lib/runner/evaluation_table.hpp"
#include "lib/runner/heart_motion.hpp"
#include "engine/scene/moving_wall.hpp"
#include "task/navigation_task.hpp"
#include "engine/wire/wire_params.hpp"

namespace {

const std::string kCoronary = std::string(GW_SOURCE_DIR) + "/anatomies/test/coronary/coronary";
const std::string kDeformed = std::string(GW_SOURCE_DIR) + "/anatomies/test/coronary_deformed/coronary_deformed";

gw::Anatomy coronary() { return gw::load_anatomy("coronary", kCoronary + ".stl", kCoronary + ".truth.json"); }

}  // namespace

TEST_CASE("heart motion: the shipped coronary's own field, held at the inlet, at the asked rate", "[runner][heart]") {
  const gw::Anatomy a = coronary();
  gw::HeartSettings h;
  h.heart_rate_bpm = 100;
  const gw::HeartMotion m = gw::resolve_heart_motion(a.mesh_path, a.graph.inlet.position, h);
  CHECK(m.source.find("coronary.spec.json deformation") != std::string::npos);
  CHECK(m.motion.heart_rate_bpm == 100);
  CHECK(m.motion.contraction_mm == 0.12);  // the generator's 12% radial contraction, 10% shortening, 2.5 deg/cm
  CHECK(m.motion.shortening_mm == 0.1);
  CHECK(m.motion.twist_deg_per_cm == 2.5);
  CHECK(m.motion.axis_direction == Eigen::Vector3d(0, 0, -1));
  REQUIRE(m.motion.has_fixed_point);
  CHECK(m.motion.fixed_point == a.graph.inlet.position);
  // The deformed coronary is the field's phase 1 already: refused, not deformed twice.
  CHECK_THROWS_WITH(gw::resolve_heart_motion(kDeformed + ".stl", a.graph.inlet.position, h),
                    Catch::Contains("phase 1"));
  // No motion beside a mesh, or a spec without a field: the error asks for --motion.
  CHECK_THROWS_WITH(gw::resolve_heart_motion("/nonexistent/tube.stl", Eigen::Vector3d::Zero(), h),
                    Catch::Contains("--motion"));
  CHECK_THROWS_WITH(gw::resolve_heart_motion(std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y.stl",
                                             Eigen::Vector3d::Zero(), h),
                    Catch::Contains("--motion"));
}

TEST_CASE("heart motion: 0 bpm leaves the anatomy as it is, a beating one keeps its rest graph", "[runner][heart]") {
  gw::Anatomy a = coronary();
  const auto scene = a.scene;
  CHECK(gw::apply_heart_settings(a, gw::HeartSettings{}).empty());
  CHECK(a.scene == scene);
  gw::HeartSettings h;
  h.heart_rate_bpm = 60;
  const std::string source = gw::apply_heart_settings(a, h);
  CHECK_FALSE(source.empty());
  REQUIRE(a.scene->motion);
  CHECK(a.scene->motion->heart_rate_bpm == 60);
  const gw::NavigationTask task = gw::make_navigation_task({}, gw::default_wire_params(), {a});
  CHECK(task.graph_motions[0].points > 0);
  // The inlet (the introducer) stays put; the far end of the tree moves by millimetres at end-systole.
  const double systole = 60.0 / 60.0 / 3.0;
  CHECK((gw::current_wall_vertex(*a.scene, 0, 0.0) - a.scene->mesh.V.row(0).transpose()).norm() == 0.0);
  gw::CenterlineGraph now;
  gw::graph_at(a.graph, *a.scene, task.graph_motions[0], systole, now);
  CHECK((now.inlet.position - a.graph.inlet.position).norm() < 1e-12);
  double moved = 0;
  for (size_t k = 0; k < a.graph.targets.size(); ++k)
    moved = std::max(moved, (now.targets[k].position - a.graph.targets[k].position).norm());
  CHECK(moved > 3.0);
}

TEST_CASE("heart motion: a motion frozen in a deformed shape (0 bpm at a phase offset) moves the centerline too",
          "[runner][heart]") {
  gw::Anatomy a = coronary();
  const gw::CenterlineGraph rest = a.graph;
  gw::CardiacMotion m = gw::cardiac_motion_from_spec(kCoronary + ".spec.json", a.graph.inlet.position);
  m.heart_rate_bpm = 0;
  m.phase_offset = 1.0 / 3.0;  // end-systole
  gw::make_anatomy_beat(a, m);
  CHECK_FALSE(a.scene->motion);  // a static scene of the frozen shape
  const gw::WallMotion field = gw::cardiac_wall_motion(coronary().scene->mesh, m);
  Eigen::Vector3d x;
  REQUIRE(gw::wall_field_position(field, rest.targets[0].position, 0.0, x));
  CHECK((a.graph.targets[0].position - x).norm() < 1e-9);
  CHECK((a.graph.targets[0].position - rest.targets[0].position).norm() > 1.0);
  CHECK(a.branch_lines[0].points.front() == a.graph.branches[0].points.front());
}

TEST_CASE("evaluate: the beating coronary rows follow the paper's rows, which are unchanged", "[runner][heart]") {
  const std::vector<gw::EvaluationRow> table = gw::paper_table();
  REQUIRE(table.size() >= 12);
  CHECK(table[8].name == "coronary-like");
  CHECK(table[9].name == "deformed coronary");
  int beating = 0;
  for (const gw::EvaluationRow& row : table) {
    if (row.name.rfind("beating coronary", 0) != 0) {
      CHECK(row.heart_rate_bpm == 0);  // every other row: a static wall, its episodes as before
      continue;
    }
    ++beating;
    CHECK(row.anatomies == std::vector<std::string>{"coronary"});
    CHECK(row.episodes == 50);
    CHECK(row.name == "beating coronary " + std::to_string(static_cast<int>(row.heart_rate_bpm)) + " bpm");
  }
  CHECK(beating == 2);
  CHECK(gw::select_rows(table, "coronary 60 bpm").at(0).heart_rate_bpm == 60);
  CHECK(gw::select_rows(table, "coronary 100 bpm").at(0).heart_rate_bpm == 100);
}

namespace {

// An OBJ of `mesh` with its vertices moved by `shift` (same vertex order and triangles).
void write_obj(const std::filesystem::path& path, const gw::TriangleMesh& mesh, const Eigen::Vector3d& shift) {
  std::ofstream out(path);
  out.precision(17);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    out << "v " << mesh.V(i, 0) + shift.x() << " " << mesh.V(i, 1) + shift.y() << " " << mesh.V(i, 2) + shift.z() << "\n";
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    out << "f " << mesh.F(f, 0) + 1 << " " << mesh.F(f, 1) + 1 << " " << mesh.F(f, 2) + 1 << "\n";
}

}  // namespace

TEST_CASE("heart motion: 4D CT phase surfaces from a motion file move the wall through them", "[runner][heart]") {
  // Three phases of the t1 tree (the rest mesh, shifted 0.6 mm in x, shifted 0.6 mm in y) written as OBJ, and
  // a motion file naming them: at 60 bpm the wall is at phase j / 3 at t = j / 3 s, in between interpolated.
  const std::string stem = std::string(GW_SOURCE_DIR) + "/anatomies/train/t1_straight_y/t1_straight_y";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gw_phase_surfaces_test";
  std::filesystem::create_directories(dir);
  gw::Anatomy a = gw::load_anatomy("t1", stem + ".stl", stem + ".truth.json");
  const gw::TriangleMesh rest = a.scene->mesh;
  write_obj(dir / "p0.obj", rest, Eigen::Vector3d::Zero());
  write_obj(dir / "p1.obj", rest, Eigen::Vector3d(0.6, 0, 0));
  write_obj(dir / "p2.obj", rest, Eigen::Vector3d(0, 0.6, 0));
  std::ofstream(dir / "motion.json")
      << R"({"heart_rate_bpm": 60, "phase_surfaces": ["p0.obj", "p1.obj", "p2.obj"], "fixed_point": "none"})";
  gw::HeartSettings h;
  h.motion_path = (dir / "motion.json").string();
  CHECK(gw::apply_heart_settings(a, h) == h.motion_path);
  REQUIRE(a.scene->motion);
  CHECK(a.scene->motion->kind == gw::WallMotionKind::phases);
  // (1e-6: the mesh reader keeps coordinates in single precision.)
  for (const int v : {0, 100, static_cast<int>(rest.V.rows()) - 1}) {
    const Eigen::Vector3d X = rest.V.row(v).transpose();
    CHECK((gw::current_wall_vertex(*a.scene, v, 1.0 / 3.0) - (X + Eigen::Vector3d(0.6, 0, 0))).norm() < 1e-6);
    CHECK((gw::current_wall_vertex(*a.scene, v, 2.0 / 3.0) - (X + Eigen::Vector3d(0, 0.6, 0))).norm() < 1e-6);
    CHECK((gw::current_wall_vertex(*a.scene, v, 0.5) - (X + Eigen::Vector3d(0.3, 0.3, 0))).norm() < 1e-6);
    CHECK((gw::current_wall_vertex(*a.scene, v, 1.0) - X).norm() < 1e-6);  // one cycle later: phase 0 again
  }
  // The task follows the moving wall: its centerline at t is mapped through the surfaces (graph_motion.hpp).
  gw::NavigationTask task = gw::make_navigation_task({}, gw::default_wire_params(), {a});
  CHECK(task.anatomies.size() == 1);

  // Held at the inlet (a motion file's default): these phases are translations, so nothing moves.
  std::ofstream(dir / "held.json") << R"({"heart_rate_bpm": 60, "phase_surfaces": ["p0.obj", "p1.obj", "p2.obj"]})";
  gw::Anatomy held = gw::load_anatomy("t1", stem + ".stl", stem + ".truth.json");
  h.motion_path = (dir / "held.json").string();
  CHECK(gw::apply_heart_settings(held, h) == h.motion_path + ", held at the inlet");
  for (const int v : {0, 100, static_cast<int>(rest.V.rows()) - 1})
    for (const double t : {1.0 / 3.0, 0.5, 2.0 / 3.0})
      CHECK((gw::current_wall_vertex(*held.scene, v, t) - rest.V.row(v).transpose()).norm() < 1e-6);

  // A surface with other triangles, a motion file mixing phase surfaces with a parametric key: refused, named.
  gw::TriangleMesh fewer = rest;
  fewer.F.conservativeResize(rest.F.rows() - 1, 3);
  write_obj(dir / "bad.obj", fewer, Eigen::Vector3d::Zero());
  std::ofstream(dir / "bad_motion.json") << R"({"heart_rate_bpm": 60, "phase_surfaces": ["p0.obj", "bad.obj"]})";
  gw::Anatomy b = gw::load_anatomy("t1", stem + ".stl", stem + ".truth.json");
  h.motion_path = (dir / "bad_motion.json").string();
  CHECK_THROWS_WITH(gw::apply_heart_settings(b, h), Catch::Contains("bad.obj") && Catch::Contains("same mesh moved"));
  std::ofstream(dir / "mixed.json") << R"({"phase_surfaces": ["p0.obj", "p1.obj"], "contraction_mm": 1})";
  CHECK_THROWS_WITH(gw::load_cardiac_motion((dir / "mixed.json").string()),
                    Catch::Contains("mixed.json") && Catch::Contains("contraction_mm"));
  std::ofstream(dir / "one.json") << R"({"phase_surfaces": ["p0.obj"]})";
  CHECK_THROWS_WITH(gw::load_cardiac_motion((dir / "one.json").string()), Catch::Contains("at least two"));
}

TEST_CASE("heart motion: a motion file holds the inlet still unless it says otherwise", "[runner][heart]") {
  // A translation only (5 mm at end-systole): held at the inlet (the file's default, the guide catheter's
  // frame) it moves nothing against the introducer; with "fixed_point": "none" the whole wall, inlet
  // included, moves away from it by the translation.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gw_held_inlet_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "held.json") << R"({"heart_rate_bpm": 60, "translation_mm": [3, 4, 0]})";
  std::ofstream(dir / "free.json") << R"({"heart_rate_bpm": 60, "translation_mm": [3, 4, 0], "fixed_point": "none"})";
  std::ofstream(dir / "bad.json") << R"({"translation_mm": [3, 4, 0], "fixed_point": "ostium"})";
  const double systole = 1.0 / 3.0;  // 60 bpm: end-systole at a third of the 1 s cycle
  gw::HeartSettings h;

  gw::Anatomy held = coronary();
  h.motion_path = (dir / "held.json").string();
  CHECK(gw::load_cardiac_motion(h.motion_path).hold_inlet);
  const gw::HeartMotion m = gw::resolve_heart_motion(held.mesh_path, held.graph.inlet.position, h);
  REQUIRE(m.motion.has_fixed_point);
  CHECK(m.motion.fixed_point == held.graph.inlet.position);
  CHECK(m.source.find("held at the inlet") != std::string::npos);
  gw::apply_heart_settings(held, h);
  REQUIRE(held.scene->motion);
  for (const int v : {0, 1000, static_cast<int>(held.scene->mesh.V.rows()) - 1})
    CHECK((gw::current_wall_vertex(*held.scene, v, systole) - held.scene->mesh.V.row(v).transpose()).norm() < 1e-9);

  gw::Anatomy free = coronary();
  h.motion_path = (dir / "free.json").string();
  CHECK_FALSE(gw::load_cardiac_motion(h.motion_path).hold_inlet);
  gw::apply_heart_settings(free, h);
  REQUIRE(free.scene->motion);
  for (const int v : {0, 1000})
    CHECK((gw::current_wall_vertex(*free.scene, v, systole) - free.scene->mesh.V.row(v).transpose() -
           Eigen::Vector3d(3, 4, 0)).norm() < 1e-9);

  CHECK_THROWS_WITH(gw::load_cardiac_motion((dir / "bad.json").string()),
                    Catch::Contains("bad.json") && Catch::Contains("fixed_point") && Catch::Contains("inlet"));
  // The engine refuses a motion that asks to hold an inlet nobody gave it.
  gw::CardiacMotion asks;
  asks.hold_inlet = true;
  CHECK_THROWS_WITH(gw::heart_wall_motion(held.scene->mesh, asks), Catch::Contains("inlet"));
}
