// The mesh-info command: exit status and a single error line for bad input.
#include <catch2/catch.hpp>
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

#include "mesh_files.hpp"

namespace {
struct Run {
  int status;
  std::string output;
};

Run run(const std::string& args) {
  const std::string cmd = std::string(GW_BINARY_DIR) + "/apps/mesh-info " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}
}  // namespace

TEST_CASE("mesh-info prints a report for a good mesh and one error line for a bad one", "[mesh][cli]") {
  gw::TriangleMesh cube = gw::test::unit_cube();
  cube.V *= 30.0;
  const std::string good = gw::test::scratch_path("cli_cube.stl"), bad = gw::test::scratch_path("cli_empty.stl");
  gw::test::write_binary_stl(good, cube);
  gw::test::write_text(bad, "");

  const Run ok = run("--anatomy " + good);
  CHECK(ok.status == 0);
  CHECK(ok.output.find("faces               12") != std::string::npos);

  const Run json = run("--anatomy " + good + " --json");
  CHECK(json.status == 0);
  CHECK(json.output.find("\"closed\":true") != std::string::npos);

  const Run empty = run("--anatomy " + bad);
  CHECK(empty.status == 1);
  CHECK(empty.output == "error: " + bad + ": empty file\n");

  const Run metres = run("--anatomy " + good + " --scale 0.001");
  CHECK(metres.status == 0);
  CHECK(metres.output.find("probably in metres") != std::string::npos);
}
