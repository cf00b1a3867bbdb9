#include "apps/report/png_encoder.hpp"

#include <stdexcept>

#include "apps/report/atomic_write.hpp"
#include "apps/report/checksums.hpp"

namespace gw {
namespace {

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

// length, type, data, CRC over type + data (PNG spec 5.3).
void chunk(std::vector<std::uint8_t>& out, const char type[4], const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, crc32(out.data() + start, out.size() - start));
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& img, DeflateMode mode) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgb.size() != static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3)
    throw std::invalid_argument("encode_png: image " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                                " has " + std::to_string(img.rgb.size()) + " bytes of pixels");
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  put32(ihdr, static_cast<std::uint32_t>(img.width));
  put32(ihdr, static_cast<std::uint32_t>(img.height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type 2 (RGB), deflate, filter set 0, no interlace
  chunk(out, "IHDR", ihdr);

  const std::size_t stride = static_cast<std::size_t>(img.width) * 3;
  std::vector<std::uint8_t> raw;
  raw.reserve((stride + 1) * static_cast<std::size_t>(img.height));
  for (int y = 0; y < img.height; ++y) {
    raw.push_back(0);  // filter type None: LZ77 already finds the repeats of flat figures
    const auto row = img.rgb.begin() + static_cast<std::ptrdiff_t>(stride * static_cast<std::size_t>(y));
    raw.insert(raw.end(), row, row + static_cast<std::ptrdiff_t>(stride));
  }
  chunk(out, "IDAT", zlib_compress(raw.data(), raw.size(), mode));
  chunk(out, "IEND", {});
  return out;
}

void write_png(const Image& img, const std::string& path, DeflateMode mode) {
  const std::vector<std::uint8_t> bytes = encode_png(img, mode);
  write_file_atomic(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace gw
