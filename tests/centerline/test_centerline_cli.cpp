// The centerline command: JSON out, --list, --out, cache, and one error line for bad input.
#include <catch2/catch.hpp>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

#include "base/graph/centerline_graph.hpp"
#include "tube_mesh.hpp"
#include "../mesh/mesh_files.hpp"

namespace {
struct Run {
  int status;
  std::string output;
};

Run run(const std::string& args) {
  const std::string cmd = std::string(GW_BINARY_DIR) + "/apps/centerline " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}
}  // namespace

TEST_CASE("centerline command: graph JSON, target table, cache, errors", "[centerline][cli]") {
  using namespace gw;
  const std::string mesh = test::scratch_path("cli_tube.stl"), empty = test::scratch_path("cli_empty.stl");
  const std::string cache = test::scratch_path("cli_cache"), out = test::scratch_path("cli_out.json");
  std::filesystem::remove_all(cache);
  std::filesystem::remove(out);
  test::write_binary_stl(mesh, test::make_tube(test::arc_axis(0.0, 15.0, M_PI / 2, 90), 2.0, 24, true));
  test::write_text(empty, "");
  const std::string common = " --cache-dir " + cache;

  const Run json = run("--anatomy " + mesh + " --inlet 0,0,0" + common);
  REQUIRE(json.status == 0);
  const CenterlineGraph g = centerline_from_json(json.output);
  REQUIRE(g.targets.size() == 1);
  CHECK(g.inlet.position.norm() < 0.5);
  CHECK((g.targets[0].position - Eigen::Vector3d(15, 15, 0)).norm() < 0.5);

  const Run list = run("--anatomy " + mesh + " --inlet 0,0,0 --list --verbose" + common);
  CHECK(list.status == 0);
  CHECK(list.output.find("from cache") != std::string::npos);
  CHECK(list.output.find("1 target(s), 0 bifurcation(s)") != std::string::npos);
  CHECK(list.output.find("path (mm)") != std::string::npos);

  const Run file = run("--anatomy " + mesh + " --inlet 0,0,0 --out " + out + common);
  CHECK(file.status == 0);
  CHECK(file.output.empty());
  CHECK(read_centerline(out).targets.size() == 1);

  // Without --inlet the widest end is a guess, and a tube of constant radius has two: say so.
  const Run guessed = run("--anatomy " + mesh + " --out " + out + common);
  CHECK(guessed.status == 0);
  CHECK(guessed.output.rfind("warning: " + mesh + ": the inlet was guessed as the widest vessel end", 0) == 0);
  CHECK(guessed.output.find("pass --inlet x,y,z") != std::string::npos);

  const Run missing = run("--anatomy /nonexistent/vessel.stl" + common);
  CHECK(missing.status == 1);
  CHECK(missing.output.rfind("error: /nonexistent/vessel.stl: ", 0) == 0);

  const Run bad_file = run("--anatomy " + empty + common);
  CHECK(bad_file.status == 1);
  CHECK(bad_file.output == "error: " + empty + ": empty file\n");

  const Run bad_inlet = run("--anatomy " + mesh + " --inlet 1,2" + common);
  CHECK(bad_inlet.status == 1);
  CHECK(bad_inlet.output.find("error: --inlet: expected x,y,z") == 0);

  const Run metres = run("--anatomy " + mesh + " --scale 0.001" + common);
  CHECK(metres.status == 1);
  CHECK(metres.output.find("error: " + mesh + ": vessel radius is about 0.00") != std::string::npos);
  CHECK(metres.output.find("--scale") != std::string::npos);

  const Run bad_out = run("--anatomy " + mesh + " --inlet 0,0,0 --out /nonexistent/dir/x.json" + common);
  CHECK(bad_out.status == 1);
  CHECK(bad_out.output.find("/nonexistent/dir/x.json: cannot open for writing") != std::string::npos);
  CHECK(bad_out.output.rfind("error: ", 0) == 0);
}
