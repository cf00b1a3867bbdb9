// Loading every supported format, welding, scaling, and each bad-input case.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>

#include "base/mesh/load_mesh.hpp"
#include "base/mesh/validate_mesh.hpp"
#include "mesh_files.hpp"

using namespace gw;
using Catch::Matchers::Contains;

namespace {
std::string error_of(const std::string& path) {
  try {
    load_valid_mesh(path);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("binary and ASCII STL, OBJ and PLY load to the same welded cube", "[mesh]") {
  const TriangleMesh cube = test::unit_cube();
  const std::string bin = test::scratch_path("cube_bin.stl"), ascii = test::scratch_path("cube_ascii.stl"),
                    obj = test::scratch_path("cube.obj"), ply = test::scratch_path("cube.ply");
  test::write_binary_stl(bin, cube);
  test::write_ascii_stl(ascii, cube);
  test::write_obj(obj, cube);
  test::write_ply(ply, cube);
  for (const std::string& path : {bin, ascii, obj, ply}) {
    INFO(path);
    const TriangleMesh m = load_mesh(path);
    CHECK(m.V.rows() == 8);  // STL stores 36 corners: welding must merge them
    CHECK(m.F.rows() == 12);
    const MeshReport r = validate_mesh(m);
    CHECK(r.closed());
    CHECK(r.manifold());
    CHECK(r.components == 1);
    CHECK(r.volume == Approx(1.0));  // outward winding preserved
  }
}

TEST_CASE("scale multiplies coordinates", "[mesh]") {
  const std::string path = test::scratch_path("cube_scale.stl");
  test::write_binary_stl(path, test::unit_cube());
  const TriangleMesh m = load_mesh(path, {1000.0});
  CHECK(m.V.maxCoeff() == Approx(1000.0));
  CHECK(validate_mesh(m).volume == Approx(1e9));
  CHECK_THROWS_WITH(load_mesh(path, {-2.0}), Contains("scale must be a positive"));
}

TEST_CASE("bad files give one clear error naming the file and the problem", "[mesh][errors]") {
  SECTION("missing file") {
    const std::string path = test::scratch_path("does_not_exist.stl");
    std::filesystem::remove(path);
    const std::string e = error_of(path);
    CHECK_THAT(e, Contains(path) && Contains("no such file"));
  }
  SECTION("empty file") {
    const std::string path = test::scratch_path("empty.stl");
    test::write_text(path, "");
    CHECK_THAT(error_of(path), Contains(path) && Contains("empty file"));
  }
  SECTION("truncated binary STL") {
    const std::string full = test::scratch_path("full.stl"), cut = test::scratch_path("truncated.stl");
    test::write_binary_stl(full, test::unit_cube());
    const auto size = std::filesystem::file_size(full);
    std::filesystem::copy_file(full, cut, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(cut, size - 70);  // drop the last facet and a half
    CHECK_THAT(error_of(cut), Contains(cut) && Contains("truncated binary STL"));
    std::filesystem::resize_file(cut, 40);  // not even a header
    CHECK_THAT(error_of(cut), Contains("truncated binary STL"));
  }
  SECTION("text that is not a mesh") {
    const std::string stl = test::scratch_path("notes.stl"), obj = test::scratch_path("notes.obj");
    test::write_text(stl, "These are my notes about the patient, not a mesh at all.\n");
    test::write_text(obj, "hello world\nthis is not an obj file\n");
    CHECK_THAT(error_of(stl), Contains(stl));
    CHECK_FALSE(error_of(stl).empty());
    CHECK_THAT(error_of(obj), Contains(obj));
    CHECK_FALSE(error_of(obj).empty());
  }
  SECTION("NaN coordinates") {
    TriangleMesh cube = test::unit_cube();
    cube.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
    const std::string path = test::scratch_path("nan.stl");
    test::write_binary_stl(path, cube);
    CHECK_THAT(error_of(path), Contains(path) && Contains("NaN"));
    CHECK_NOTHROW(load_mesh(path));  // raw loading works; validation refuses
  }
  SECTION("unsupported extension") {
    const std::string path = test::scratch_path("cube.txt");
    test::write_text(path, "1 2 3");
    CHECK_THAT(error_of(path), Contains("unsupported extension"));
  }
  SECTION("a directory") {
    const std::string path = test::scratch_path("a_directory.stl");
    std::filesystem::create_directories(path);
    CHECK_THAT(error_of(path), Contains("directory"));
  }
}
