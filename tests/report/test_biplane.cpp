// The biplane figure: what is drawn where (target, vessel, background, traces, wire),
// framing robust to diverged traces, the PNG file, and the principal-axis views.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "lib/report/atomic_write.hpp"
#include "lib/report/biplane_render.hpp"
#include "lib/report/palette.hpp"
#include "base/mesh/load_mesh.hpp"
#include "png_decode.hpp"
#include "report_scenes.hpp"

using namespace gw;
namespace pal = gw::palette;

namespace Catch {
template <>
struct StringMaker<gw::Rgb> {
  static std::string convert(gw::Rgb c) {
    return "rgb(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + ")";
  }
};
}  // namespace Catch

namespace {

Rgb pixel(const BiplaneRender& r, int view, const Eigen::Vector3d& p) {
  const Eigen::Vector2d px = r.views[static_cast<std::size_t>(view)].to_pixel(p);
  return r.image.at(static_cast<int>(std::floor(px.x())), static_cast<int>(std::floor(px.y())));
}

bool is_grey(Rgb c) { return c.r == c.g && c.g == c.b && c.r < 255 && c.r >= 140; }

BiplaneOptions fixed_axes() {
  BiplaneOptions o;
  o.axes = BiplaneAxes::FixedXY_ZY;
  return o;
}

}  // namespace

TEST_CASE("biplane: target, vessel, background, trace and wire pixels are where they project", "[report][biplane]") {
  const TriangleMesh mesh = test::box_vessel();
  const CenterlineGraph graph = test::straight_graph();
  const TargetPath path = plan_path(graph, 1);
  const EpisodeTrace trace = test::box_trace();
  const BiplaneRender r = render_biplane(mesh, graph, path.points, graph.targets[0], {trace}, {"box test"}, fixed_axes());

  REQUIRE(r.image.width == 1400);
  REQUIRE(r.image.height == 700);
  // Frontal: right = +x, up = +y; lateral: right = +z, up = +y (documented fixed axes).
  CHECK(r.views[0].axes.right == Eigen::Vector3d::UnitX());
  CHECK(r.views[1].axes.right == Eigen::Vector3d::UnitZ());
  const Eigen::Vector2d a = r.views[0].to_pixel({0, 0, 0}), b = r.views[0].to_pixel({0, 40, 0});
  CHECK(b.y() < a.y());  // up is up
  // Same scale in both panels, and the panels do not overlap.
  CHECK(r.views[0].px_per_mm == r.views[1].px_per_mm);
  CHECK(r.views[0].panel_origin.x() + r.views[0].panel_size.x() <= r.views[1].panel_origin.x());

  for (int v = 0; v < 2; ++v) {
    CAPTURE(v);
    // (x, y, z) in the frontal view; the lateral view sees z where the frontal sees x.
    auto at = [&](double side, double y) {
      return v == 0 ? Eigen::Vector3d(side, y, 0.0) : Eigen::Vector3d(0.0, y, side);
    };
    CHECK(pixel(r, v, graph.targets[0].position) == pal::kTarget);
    // The path; in the lateral view the tip trace (x = -1) and the final wire (x = +1.5) lie on top of it.
    CHECK(pixel(r, v, at(0.0, 10.0)) == (v == 0 ? pal::kPath : pal::kWire));
    CHECK(pixel(r, v, at(1.0, 20.5)) == pal::kVesselFill);  // inside the box, off everything else
    CHECK(pixel(r, v, at(15.0, 20.0)) == pal::kBackground);  // far outside the mesh
    CHECK(pixel(r, v, at(-15.0, 8.0)) == pal::kBackground);
    CHECK(pixel(r, v, {1.5, 25.0, 0.0}) == pal::kWire);  // final wire (x = +1.5)
    CHECK(pixel(r, v, {-1.0, 38.0, 0.0}) == pal::outcome_color("success"));  // final tip
    // Walking right from inside the vessel: grey fill, then the darker outline at 2 mm, then background.
    const Eigen::Vector2d from = r.views[static_cast<std::size_t>(v)].to_pixel(at(1.0, 5.0));
    int x = static_cast<int>(std::floor(from.x()));
    const int y = static_cast<int>(std::floor(from.y()));
    while (r.image.at(x + 1, y) != pal::kBackground) ++x;
    CHECK(r.image.at(x, y) == pal::kVesselEdge);
    CHECK(is_grey(r.image.at(x - 3, y)));
    CHECK(r.views[static_cast<std::size_t>(v)].to_pixel(at(2.0, 5.0)).x() == Approx(x + 0.5).margin(1.0));
  }
  // The tip trace runs at x = -1 (frontal only; in the lateral view it hides behind the path).
  CHECK(pixel(r, 0, {-1.0, 10.0, 0.0}) == pal::kTipPush);
  CHECK(pixel(r, 0, {-1.0, 30.0, 0.0}) == pal::kTipAgent);
}

TEST_CASE("biplane: trace coloured by time goes from the ramp's start to its end", "[report][biplane]") {
  const CenterlineGraph graph = test::straight_graph();
  BiplaneOptions o = fixed_axes();
  o.coloring = TraceColoring::Time;
  o.draw_final_wire = false;
  const EpisodeTrace t = test::box_trace();
  const BiplaneRender r = render_biplane(test::box_vessel(), graph, plan_path(graph, 1).points, graph.targets[0], {t}, {}, o);
  // The segment from frame i-1 to frame i has frame i's colour (t = 0.1 i of 3.8 s).
  CHECK(pixel(r, 0, {-1.0, 2.5, 0.0}) == pal::time_color(t.time_s[3] / t.time_s.back()));
  CHECK(pixel(r, 0, {-1.0, 30.5, 0.0}) == pal::time_color(t.time_s[31] / t.time_s.back()));
  CHECK(pal::time_color(0.0) != pal::time_color(1.0));
  CHECK(pixel(r, 0, {1.5, 25.0, 0.0}) == pal::kVesselFill);  // no wire drawn
}

TEST_CASE("biplane: a diverged trace (NaN, huge values) neither crashes nor reframes the views", "[report][biplane]") {
  const CenterlineGraph graph = test::straight_graph();
  const auto path = plan_path(graph, 1).points;
  const BiplaneRender ref = render_biplane(test::box_vessel(), graph, path, graph.targets[0], {}, {}, fixed_axes());
  EpisodeTrace t = test::box_trace();
  t.outcome = "diverged";
  t.detail = "NaN in the wire state at t = 3.9 s";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  t.time_s.push_back(3.9);
  t.tip.emplace_back(nan, nan, nan);
  t.action.push_back(nan);
  t.agent_in_control.push_back(true);
  t.time_s.push_back(4.0);
  t.tip.emplace_back(1e9, -1e12, 3e15);
  t.action.push_back(0.0);
  t.agent_in_control.push_back(true);
  t.wire_shapes.push_back({{0, 0, 0}, {nan, 1, 1}, {1e10, 0, 0}});
  t.wire_shape_frame.push_back(40);
  EpisodeTrace ok = test::box_trace();
  const BiplaneRender r = render_biplane(test::box_vessel(), graph, path, graph.targets[0], {ok, t}, {}, fixed_axes());
  for (int v = 0; v < 2; ++v) {
    CHECK(r.views[static_cast<std::size_t>(v)].px_per_mm == ref.views[static_cast<std::size_t>(v)].px_per_mm);
    CHECK(pixel(r, v, graph.targets[0].position) == pal::kTarget);
  }
}

TEST_CASE("biplane: principal axes put the longest spread vertical with the inlet on top", "[report][biplane]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector3d long_dir = Eigen::Vector3d(1, 1, 0).normalized(), mid_dir = Eigen::Vector3d::UnitZ(),
                        short_dir = Eigen::Vector3d(1, -1, 0).normalized();
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 2000; ++i) cloud.push_back(50 * n(rng) * long_dir + 10 * n(rng) * mid_dir + 2 * n(rng) * short_dir);
  const Eigen::Vector3d inlet = -120.0 * long_dir;
  const auto axes = choose_biplane_axes(cloud, inlet, BiplaneAxes::Principal);
  for (const auto& a : axes) {
    CHECK(a.right.norm() == Approx(1.0));
    CHECK(a.up.norm() == Approx(1.0));
    CHECK(a.right.dot(a.up) == Approx(0.0).margin(1e-9));
  }
  CHECK(axes[0].up.dot(long_dir) == Approx(-1.0).margin(0.02));  // inlet at -long: up points to -long
  CHECK(axes[0].up == axes[1].up);
  CHECK(std::abs(axes[0].right.dot(mid_dir)) == Approx(1.0).margin(0.02));
  CHECK(axes[0].right.z() > 0.0);  // sign rule: largest component positive
  CHECK(std::abs(axes[1].right.dot(short_dir)) == Approx(1.0).margin(0.02));
  CHECK(axes[1].right.dot(axes[0].right) == Approx(0.0).margin(1e-9));
  // The inlet projects above the centre of the cloud.
  CHECK(inlet.dot(axes[0].up) > 0.0);
  CHECK_THROWS_AS(choose_biplane_axes({}, inlet, BiplaneAxes::Principal), std::invalid_argument);
}

TEST_CASE("biplane: the PNG has the requested size and decodes to the rendered pixels", "[report][biplane]") {
  const test::TreeScene s = test::small_tree();
  const TargetPath path = plan_path(s.graph, 2);
  const EpisodeTrace t = test::episode_along(path.points, s.graph, "success", "", 2);
  BiplaneOptions o;
  o.width = 640;
  o.height = 360;
  const std::string dir = test::scratch_dir("biplane");
  const std::string file = dir + "/tree.png";
  render_biplane_png(s.mesh, s.graph, path.points, s.graph.targets[1], {t}, {"small tree"}, file, o);
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const test::DecodedPng decoded = test::decode_png(png);
  CHECK(decoded.width == 640);
  CHECK(decoded.height == 360);
  const auto& raw = decoded.rgb;
  const BiplaneRender r = render_biplane(s.mesh, s.graph, path.points, s.graph.targets[1], {t}, {"small tree"}, o);
  const Eigen::Vector2d tp = r.views[1].to_pixel(s.graph.targets[1].position);
  const std::size_t at = static_cast<std::size_t>(std::floor(tp.y())) * (3 * 640u) +
                         3 * static_cast<std::size_t>(std::floor(tp.x()));
  CHECK(Rgb{raw[at], raw[at + 1], raw[at + 2]} == pal::kTarget);
  CHECK(raw == r.image.rgb);  // every pixel as rendered
}

TEST_CASE("biplane: bad sizes, bad traces and unwritable paths are clear errors", "[report][biplane]") {
  const CenterlineGraph graph = test::straight_graph();
  const auto path = plan_path(graph, 1).points;
  BiplaneOptions tiny;
  tiny.width = 200;
  CHECK_THROWS_WITH(render_biplane(test::box_vessel(), graph, path, graph.targets[0], {}, {}, tiny),
                    Catch::Matchers::Contains("200x700"));
  EpisodeTrace bad = test::box_trace();
  bad.action.pop_back();
  CHECK_THROWS_WITH(render_biplane(test::box_vessel(), graph, path, graph.targets[0], {bad}, {}),
                    Catch::Matchers::Contains("action has 38 frames"));
  const std::string out = test::scratch_dir("biplane_bad") + "/missing/dir/fig.png";
  CHECK_THROWS_AS(render_biplane_png(test::box_vessel(), graph, path, graph.targets[0], {}, {}, out), ReportError);
  CHECK_THROWS_WITH(render_biplane_png(test::box_vessel(), graph, path, graph.targets[0], {}, {}, out), Catch::Matchers::Contains(out));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("biplane: example figure of a small tree (written to the build tree for a look)", "[report][biplane][example]") {
  const test::TreeScene s = test::small_tree();
  REQUIRE(s.graph.targets.size() == 3);
  const TargetPath path = plan_path(s.graph, 3);
  // The wire took the wrong child at the second bifurcation: route = path to B1, then the other child.
  const int wrong = path.bifurcations.back().wrong_children.at(0);
  std::vector<Eigen::Vector3d> route;
  for (int b : {0, 2}) route.insert(route.end(), s.graph.branches[static_cast<std::size_t>(b)].points.begin() + (b ? 1 : 0),
                                    s.graph.branches[static_cast<std::size_t>(b)].points.end());
  const auto& wb = s.graph.branches[static_cast<std::size_t>(wrong)].points;
  route.insert(route.end(), wb.begin() + 1, wb.begin() + static_cast<std::ptrdiff_t>(wb.size() / 2));
  const EpisodeTrace t = test::episode_along(
      route, s.graph, "wrong_branch",
      "at bifurcation B" + std::to_string(path.bifurcations.back().bifurcation) + " entered branch " + std::to_string(wrong), 3);
  const std::string file = std::string(GW_BINARY_DIR) + "/report_example_biplane.png";
  render_biplane_png(s.mesh, s.graph, path.points, s.graph.targets[2], {t},
                     {"synthetic 3-target tree, target 3 (example figure of gw_report)"}, file);
  CHECK(std::filesystem::file_size(file) < 200u * 1024u);
}

TEST_CASE("biplane: a real anatomy (coronary) renders with its vessel, path and target visible", "[report][biplane][anatomy]") {
  const std::string dir = std::string(GW_SOURCE_DIR) + "/anatomies/test/coronary/";
  REQUIRE(std::filesystem::exists(dir + "coronary.stl"));  // shipped with the repository: missing is a failure
  const TriangleMesh mesh = load_mesh(dir + "coronary.stl");
  const CenterlineGraph graph = read_centerline(dir + "coronary.truth.json");
  const TargetPath path = plan_path(graph, 3);
  EpisodeTrace t = test::episode_along(path.points, graph, "success", "reached target 3", 3);
  t.anatomy = "coronary";
  t.controller = "illustrative trace";
  const std::string file = std::string(GW_BINARY_DIR) + "/report_coronary_biplane.png";
  const std::vector<std::string> title = {"anatomies/test/coronary, target 3: illustrative trace along the planned path "
                                          "(synthetic, not a simulation)"};
  render_biplane_png(mesh, graph, path.points, graph.targets[2], {t}, title, file);
  CHECK(std::filesystem::file_size(file) < 200u * 1024u);
  const BiplaneRender r = render_biplane(mesh, graph, path.points, graph.targets[2], {t}, title);
  for (int v = 0; v < 2; ++v) {
    CAPTURE(v);
    CHECK(pixel(r, v, graph.targets[2].position) == pal::kTarget);
    // The vessel tree is a visible silhouette: a fair share of each panel is grey.
    const ViewProjection& view = r.views[static_cast<std::size_t>(v)];
    long grey = 0;
    for (int y = view.panel_origin.y(); y < view.panel_origin.y() + view.panel_size.y(); ++y)
      for (int x = view.panel_origin.x(); x < view.panel_origin.x() + view.panel_size.x(); ++x)
        grey += is_grey(r.image.at(x, y)) ? 1 : 0;
    CHECK(grey > view.panel_size.prod() / 50);
    // Every other target is inside its panel.
    for (const Terminal& other : graph.targets) {
      const Eigen::Vector2d p = view.to_pixel(other.position);
      CHECK(p.x() > view.panel_origin.x());
      CHECK(p.x() < view.panel_origin.x() + view.panel_size.x());
      CHECK(p.y() > view.panel_origin.y());
      CHECK(p.y() < view.panel_origin.y() + view.panel_size.y());
    }
  }
}

TEST_CASE("biplane: an outcome detail too long for the big headline is wrapped below it in the outcome colour",
          "[report][biplane]") {
  const CenterlineGraph graph = test::straight_graph();
  const auto path = plan_path(graph, 1).points;
  EpisodeTrace t = test::box_trace();
  t.outcome = "diverged";
  auto detail_pixels = [&](const EpisodeTrace& trace) {
    const BiplaneRender r = render_biplane(test::box_vessel(), graph, path, graph.targets[0], {trace}, {}, fixed_axes());
    long n = 0;
    for (int y = 40; y < 66; ++y)  // the line under the scale-3 headline
      for (int x = 0; x < r.image.width; ++x) n += r.image.at(x, y) == pal::outcome_color("diverged") ? 1 : 0;
    return n;
  };
  t.detail = "NaN";
  CHECK(detail_pixels(t) == 0);
  t.detail = "physics diverged: wire point 339 is 0.509521 mm outside the vessel wall (t = 4.640000 s) after 117 steps";
  CHECK(detail_pixels(t) > 100);
}

TEST_CASE("biplane: one episode's wire is drawn over its trace, several episodes' wires under theirs",
          "[report][biplane]") {
  const CenterlineGraph graph = test::straight_graph();
  const auto path = plan_path(graph, 1).points;
  EpisodeTrace on_wire = test::box_trace();
  for (auto& p : on_wire.tip) p.x() = 1.5;  // the tip ran where the final wire lies
  const Eigen::Vector3d probe(1.5, 25.0, 0.0);
  const BiplaneRender one = render_biplane(test::box_vessel(), graph, path, graph.targets[0], {on_wire}, {}, fixed_axes());
  CHECK(pixel(one, 0, probe) == pal::kWire);
  const BiplaneRender two =
      render_biplane(test::box_vessel(), graph, path, graph.targets[0], {test::box_trace(), on_wire}, {}, fixed_axes());
  CHECK(pixel(two, 0, probe) == pal::kTipAgent);
}

TEST_CASE("biplane: a wall outline (a beating wall at end-systole) is drawn at its own silhouette's edge", "[report][biplane]") {
  const TriangleMesh mesh = test::box_vessel();
  const CenterlineGraph graph = test::straight_graph();
  const TargetPath path = plan_path(graph, 1);
  BiplaneOptions o = fixed_axes();
  TriangleMesh shifted = mesh;
  shifted.V.col(0).array() += 6.0;  // the box moved 6 mm along +x: x in [4, 8]
  const Rgb magenta{230, 0, 200};
  o.wall_outlines.push_back({shifted, magenta, "wall, end-systole"});
  o.vessel_label = "wall, end-diastole";
  const BiplaneRender r = render_biplane(mesh, graph, path.points, graph.targets[0], {}, {}, o);
  // Frontal view: walking right at y = 20 from the shifted box's middle, the outline is met at x = 8.
  const Eigen::Vector2d from = r.views[0].to_pixel({6.0, 20.0, 0.0});
  int x = static_cast<int>(std::floor(from.x()));
  const int y = static_cast<int>(std::floor(from.y()));
  CHECK(r.image.at(x, y) == pal::kBackground);  // the outline is not filled
  while (x < r.image.width - 1 && r.image.at(x, y) != magenta) ++x;
  CHECK(r.views[0].to_pixel({8.0, 20.0, 0.0}).x() == Approx(x + 0.5).margin(1.5));
  // The framing takes the outline in: both boxes are in the frontal panel.
  const Eigen::Vector2d right_edge = r.views[0].to_pixel({8.0, 20.0, 0.0});
  CHECK(right_edge.x() < r.views[0].panel_origin.x() + r.views[0].panel_size.x());
  // Inside the grey box the fill is untouched.
  CHECK(pixel(r, 0, {1.0, 20.5, 0.0}) == pal::kVesselFill);
  // Without outlines no pixel has the outline's colour.
  const BiplaneRender plain = render_biplane(mesh, graph, path.points, graph.targets[0], {}, {}, fixed_axes());
  bool any = false;
  for (int yy = 0; yy < plain.image.height && !any; ++yy)
    for (int xx = 0; xx < plain.image.width && !any; ++xx) any = plain.image.at(xx, yy) == magenta;
  CHECK_FALSE(any);
}
