#pragma once
// Reads a PNG back to 8-bit RGB pixels with libpng's simplified API (png_image), independently of
// how lib/report/png_encoder.cpp drives libpng's writer: the tests compare pixels, not bytes.
#include <png.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gw::test {

struct DecodedPng {
  int width = 0, height = 0;
  std::uint32_t format = 0;    // the file's own png_image format (PNG_FORMAT_RGB for ours)
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
};

inline DecodedPng decode_png(const std::vector<std::uint8_t>& bytes) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw std::runtime_error(std::string("not a readable PNG: ") + image.message);
  DecodedPng out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.format = image.format;
  image.format = PNG_FORMAT_RGB;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("PNG data cannot be decoded: " + message);
  }
  return out;
}

}  // namespace gw::test
