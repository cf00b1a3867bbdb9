// PNG encoder: checksums against published values, zlib streams that an independent
// decoder inflates back, and the PNG container (signature, IHDR, chunk CRCs, raw size).
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "apps/report/atomic_write.hpp"
#include "apps/report/checksums.hpp"
#include "apps/report/png_encoder.hpp"
#include "apps/report/zlib_deflate.hpp"
#include "inflate.hpp"
#include "report_scenes.hpp"

using namespace gw;

namespace {

std::vector<std::uint8_t> bytes(const std::string& s) { return {s.begin(), s.end()}; }

std::uint32_t be32(const std::vector<std::uint8_t>& d, std::size_t at) {
  return (std::uint32_t{d.at(at)} << 24) | (std::uint32_t{d.at(at + 1)} << 16) | (std::uint32_t{d.at(at + 2)} << 8) |
         d.at(at + 3);
}

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
  bool crc_ok = false;
};

// Splits a PNG into chunks, checking each CRC; throws on a truncated file.
std::vector<Chunk> parse_png(const std::vector<std::uint8_t>& png) {
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (png.size() < 8 || std::memcmp(png.data(), signature, 8) != 0) throw std::runtime_error("bad signature");
  std::vector<Chunk> chunks;
  std::size_t at = 8;
  while (at < png.size()) {
    const std::uint32_t len = be32(png, at);
    if (at + 12 + len > png.size()) throw std::runtime_error("truncated chunk");
    Chunk c;
    c.type.assign(png.begin() + static_cast<std::ptrdiff_t>(at + 4), png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    c.data.assign(png.begin() + static_cast<std::ptrdiff_t>(at + 8), png.begin() + static_cast<std::ptrdiff_t>(at + 8 + len));
    c.crc_ok = crc32(png.data() + at + 4, len + 4) == be32(png, at + 8 + len);
    chunks.push_back(std::move(c));
    at += 12 + len;
  }
  return chunks;
}

Image test_pattern(int w, int h) {
  Image img(w, h, {255, 255, 255});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x / 7 + y / 5) % 3 == 0) img.set(x, y, {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 90});
  return img;
}

}  // namespace

TEST_CASE("CRC-32 and Adler-32 match the published check values", "[report][png]") {
  const auto digits = bytes("123456789");
  CHECK(crc32(digits.data(), digits.size()) == 0xCBF43926u);
  CHECK(crc32(nullptr, 0) == 0u);
  const auto wiki = bytes("Wikipedia");
  CHECK(adler32(wiki.data(), wiki.size()) == 0x11E60398u);
  CHECK(adler32(nullptr, 0) == 1u);
  // Continuation: checksum of a whole = checksum continued over its parts.
  CHECK(crc32(digits.data() + 4, 5, crc32(digits.data(), 4)) == 0xCBF43926u);
  CHECK(adler32(wiki.data() + 3, 6, adler32(wiki.data(), 3)) == 0x11E60398u);
  // Adler-32 over more than one 5552-byte block (the modulo-deferral path).
  std::vector<std::uint8_t> big(20000, 0xFF);
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t v : big) {
    a = (a + v) % 65521;
    b = (b + a) % 65521;
  }
  CHECK(adler32(big.data(), big.size()) == ((b << 16) | a));
}

TEST_CASE("zlib streams inflate back to the input in both modes", "[report][png]") {
  std::mt19937 rng(3);
  std::vector<std::vector<std::uint8_t>> inputs = {{}, bytes("a"), bytes("abcabcabcabcabcabcabcabc"), std::vector<std::uint8_t>(70000, 7)};
  std::vector<std::uint8_t> noise(100000);
  for (auto& v : noise) v = static_cast<std::uint8_t>(rng());
  inputs.push_back(noise);
  std::vector<std::uint8_t> mixed;  // long runs, near and far repeats, literals of every value
  for (int i = 0; i < 200000; ++i) mixed.push_back(static_cast<std::uint8_t>((i % 977 < 500) ? 255 : (i * 31 / 7) % 256));
  inputs.push_back(mixed);
  for (const auto& in : inputs)
    for (DeflateMode mode : {DeflateMode::Stored, DeflateMode::FixedHuffman}) {
      CAPTURE(in.size(), mode == DeflateMode::Stored);
      const auto z = zlib_compress(in.data(), in.size(), mode);
      const test::Inflated out = test::zlib_inflate(z);
      CHECK(out.data == in);
      CHECK(out.adler_trailer == adler32(in.data(), in.size()));
      if (mode == DeflateMode::Stored) {
        CHECK(out.fixed_blocks == 0);
        CHECK(out.stored_blocks == static_cast<int>(std::max<std::size_t>(1, (in.size() + 65534) / 65535)));
      } else {
        CHECK(out.fixed_blocks == 1);
      }
    }
  // Redundant data must actually shrink with LZ77 (the point of not using stored blocks).
  const auto z = zlib_compress(mixed.data(), mixed.size(), DeflateMode::FixedHuffman);
  CHECK(z.size() < mixed.size() / 10);
}

TEST_CASE("a PNG has the signature, an IHDR of the requested size, valid CRCs and inflatable pixels", "[report][png]") {
  for (DeflateMode mode : {DeflateMode::Stored, DeflateMode::FixedHuffman}) {
    const int w = 97, h = 41;
    const Image img = test_pattern(w, h);
    const auto png = encode_png(img, mode);
    const auto chunks = parse_png(png);
    REQUIRE(chunks.size() == 3);
    CHECK(chunks[0].type == "IHDR");
    CHECK(chunks[1].type == "IDAT");
    CHECK(chunks[2].type == "IEND");
    for (const auto& c : chunks) CHECK(c.crc_ok);
    const auto& ihdr = chunks[0].data;
    REQUIRE(ihdr.size() == 13);
    CHECK(be32(ihdr, 0) == static_cast<std::uint32_t>(w));
    CHECK(be32(ihdr, 4) == static_cast<std::uint32_t>(h));
    CHECK(ihdr[8] == 8);   // bit depth
    CHECK(ihdr[9] == 2);   // RGB
    CHECK(ihdr[12] == 0);  // no interlace
    CHECK(chunks[2].data.empty());
    const test::Inflated raw = test::zlib_inflate(chunks[1].data);
    REQUIRE(raw.data.size() == static_cast<std::size_t>(h) * (1 + 3 * static_cast<std::size_t>(w)));
    CHECK(raw.adler_trailer == adler32(raw.data.data(), raw.data.size()));
    // Each row: filter byte 0, then the pixels unchanged.
    for (int y = 0; y < h; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * (1 + 3 * static_cast<std::size_t>(w));
      CHECK(raw.data[row] == 0);
      CHECK(std::equal(img.rgb.begin() + static_cast<std::ptrdiff_t>(img.index(0, y)),
                       img.rgb.begin() + static_cast<std::ptrdiff_t>(img.index(0, y) + 3 * static_cast<std::size_t>(w)),
                       raw.data.begin() + static_cast<std::ptrdiff_t>(row + 1)));
    }
  }
}

TEST_CASE("a corrupted PNG byte is caught by the chunk CRC", "[report][png]") {
  auto png = encode_png(test_pattern(20, 10));
  png[8 + 8 + 2] ^= 0x01;  // inside IHDR's width field
  const auto chunks = parse_png(png);
  CHECK_FALSE(chunks[0].crc_ok);
}

TEST_CASE("write_png writes the encoded bytes and fails cleanly on an unwritable path", "[report][png]") {
  const std::string dir = test::scratch_dir("png");
  const Image img = test_pattern(30, 20);
  const std::string path = dir + "/pattern.png";
  write_png(img, path);
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(file == encode_png(img));

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
