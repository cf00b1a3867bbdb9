// Regenerating from the committed specs reproduces the committed files byte for byte,
// and the CLI writes the same files plus a copy of the spec.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <array>
#include <cstdio>
#include <sys/wait.h>

#include "anatomy_helpers.hpp"
#include "anatomy_gen/anatomy_set.hpp"
#include "anatomy_gen/generate_anatomy.hpp"

namespace {
struct Run {
  int status;
  std::string output;
};

Run run_cli(const std::string& args) {
  const std::string cmd = std::string(GW_BINARY_DIR) + "/apps/anatomy-gen " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}
}  // namespace

TEST_CASE("regenerating a training anatomy reproduces the committed mesh and truth exactly", "[anatomy][regenerate]") {
  const std::string base = gw::test::repo("anatomies/train/t4_s_curving_back/t4_s_curving_back");
  const gw::GeneratedAnatomy a = gw::generate_anatomy(gw::read_tree_spec(base + ".spec.json"));
  const std::string dir = gw::test::scratch_dir("regenerate");
  gw::write_anatomy(a, dir);
  CHECK(gw::test::read_text(dir + "/t4_s_curving_back.stl") == gw::test::read_text(base + ".stl"));
  CHECK(gw::test::read_text(dir + "/t4_s_curving_back.truth.json") == gw::test::read_text(base + ".truth.json"));
}

TEST_CASE("the index lists exactly the committed specs", "[anatomy][regenerate]") {
  const auto specs = gw::list_anatomy_specs(gw::test::repo("anatomies"));
  const auto index = gw::test::committed_anatomies();
  REQUIRE(specs.size() == index.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    CHECK(specs[i].name == index[i].name);
    CHECK(specs[i].set == index[i].set);
  }
}

TEST_CASE("anatomy-gen CLI: summary line, outputs, spec copy, and file-named errors", "[anatomy][cli]") {
  const std::string dir = gw::test::scratch_dir("cli");
  const std::string spec = dir + "/tiny.spec.json";
  {
    std::ofstream(spec) << R"({"name": "tiny", "branches": [
      {"points": [[0,0,0],[0,0,12]], "radius": 1.5},
      {"parent": 0, "points": [[0,0,12],[-6,0,22]], "radius": 1.5},
      {"parent": 0, "points": [[0,0,12],[6,0,22]], "radius": 1.5}]})";
  }
  const Run ok = run_cli("--spec " + spec + " --out " + dir + "/out");
  INFO(ok.output);
  REQUIRE(ok.status == 0);
  const auto summary = nlohmann::json::parse(ok.output);
  CHECK(summary.at("name") == "tiny");
  CHECK(summary.at("faces").get<long>() > 1000);
  CHECK(summary.at("targets") == 2);
  CHECK(std::filesystem::exists(dir + "/out/tiny.stl"));
  CHECK(std::filesystem::exists(dir + "/out/tiny.truth.json"));
  CHECK(gw::test::read_text(dir + "/out/tiny.spec.json") == gw::test::read_text(spec));

  const std::string bad = dir + "/bad.spec.json";
  std::ofstream(bad) << R"({"name": "bad", "branches": [{"points": [[0,0,0],[0,0,12]], "radius": -1}]})";
  const Run err = run_cli("--spec " + bad + " --out " + dir + "/bad");
  CHECK(err.status == 1);
  CHECK(err.output.rfind("error: " + bad + ": ", 0) == 0);
  CHECK(err.output.find("radius must be > 0") != std::string::npos);
  CHECK(!std::filesystem::exists(dir + "/bad/bad.stl"));

  const Run no_field = run_cli("--spec " + spec + " --out " + dir + "/out2 --deform-phase 1");
  CHECK(no_field.status == 1);
  CHECK(no_field.output.find("no deformation field") != std::string::npos);
}
