// PNG files through libpng: what encode_png writes decodes (with libpng's independent simplified
// reader) to exactly the image's pixels, the header says 8-bit RGB of the image's size, a damaged
// file is refused by the decoder, and write_png is atomic.
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "lib/report/atomic_write.hpp"
#include "lib/report/png_encoder.hpp"
#include "png_decode.hpp"
#include "report_scenes.hpp"

using namespace gw;

namespace {

std::uint32_t be32(const std::vector<std::uint8_t>& d, std::size_t at) {
  return (std::uint32_t{d.at(at)} << 24) | (std::uint32_t{d.at(at + 1)} << 16) | (std::uint32_t{d.at(at + 2)} << 8) |
         d.at(at + 3);
}

Image test_pattern(int w, int h) {
  Image img(w, h, {255, 255, 255});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x / 7 + y / 5) % 3 == 0) img.set(x, y, {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 90});
  return img;
}

Image noise(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  Image img(w, h);
  for (auto& v : img.rgb) v = static_cast<std::uint8_t>(rng());
  return img;
}

}  // namespace

TEST_CASE("a PNG decodes back to the image's pixels", "[report][png]") {
  for (const Image& img : {test_pattern(97, 41), noise(64, 33, 3), Image(1, 1, {12, 34, 56}), test_pattern(1400, 700)}) {
    CAPTURE(img.width, img.height);
    const auto png = encode_png(img);
    const test::DecodedPng d = test::decode_png(png);
    CHECK(d.width == img.width);
    CHECK(d.height == img.height);
    CHECK(d.format == PNG_FORMAT_RGB);  // 8-bit RGB, no alpha, no palette
    CHECK(d.rgb == img.rgb);
  }
}

TEST_CASE("a PNG has the signature and an IHDR of 8-bit RGB without interlace", "[report][png]") {
  const auto png = encode_png(test_pattern(97, 41));
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  REQUIRE(png.size() > 33);
  CHECK(std::memcmp(png.data(), signature, 8) == 0);
  CHECK(be32(png, 8) == 13u);
  CHECK(std::string(png.begin() + 12, png.begin() + 16) == "IHDR");
  CHECK(be32(png, 16) == 97u);
  CHECK(be32(png, 20) == 41u);
  CHECK(png[24] == 8);   // bit depth
  CHECK(png[25] == 2);   // colour type RGB
  CHECK(png[28] == 0);   // no interlace
  CHECK(std::string(png.end() - 8, png.end() - 4) == "IEND");
}

TEST_CASE("flat-colour figures compress well", "[report][png]") {
  const Image img = test_pattern(1400, 700);
  CHECK(encode_png(img).size() < img.rgb.size() / 20);
}

TEST_CASE("a damaged PNG is refused by the decoder", "[report][png]") {
  auto png = encode_png(test_pattern(20, 10));
  png[8 + 8 + 2] ^= 0x01;  // inside IHDR's width field: the chunk CRC no longer matches
  CHECK_THROWS_AS(test::decode_png(png), std::runtime_error);
  auto cut = encode_png(test_pattern(20, 10));
  cut.resize(cut.size() / 2);
  CHECK_THROWS_AS(test::decode_png(cut), std::runtime_error);
}

TEST_CASE("write_png writes the encoded bytes and fails cleanly on an unwritable path", "[report][png]") {
  const std::string dir = test::scratch_dir("png");
  const Image img = test_pattern(30, 20);
  const std::string path = dir + "/pattern.png";
  write_png(img, path);
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(file == encode_png(img));
  CHECK(test::decode_png(file).rgb == img.rgb);

  const std::string bad = dir + "/no-such-dir/pattern.png";
  CHECK_THROWS_AS(write_png(img, bad), ReportError);
  CHECK_THROWS_WITH(write_png(img, bad), Catch::Matchers::Contains(bad));
  CHECK_FALSE(std::filesystem::exists(bad));
  CHECK_FALSE(std::filesystem::exists(bad + ".tmp"));
}

TEST_CASE("an image with a wrong pixel buffer is refused", "[report][png]") {
  Image img(4, 4);
  img.rgb.pop_back();
  CHECK_THROWS_AS(encode_png(img), std::invalid_argument);
  CHECK_THROWS_AS(Image(0, 5), std::invalid_argument);
}
