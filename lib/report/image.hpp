#pragma once
// An 8-bit RGB raster: what the biplane renderer draws into and the PNG encoder writes.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gw {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb a, Rgb b2) { return a.r == b2.r && a.g == b2.g && a.b == b2.b; }
  friend bool operator!=(Rgb a, Rgb b2) { return !(a == b2); }
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel

  Image() = default;
  // Throws std::invalid_argument for a non-positive or absurd (> 16384) size.
  Image(int w, int h, Rgb fill = {255, 255, 255}) : width(w), height(h) {
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384)
      throw std::invalid_argument("image size " + std::to_string(w) + "x" + std::to_string(h) +
                                  " is not between 1x1 and 16384x16384");
    rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
      rgb[i] = fill.r;
      rgb[i + 1] = fill.g;
      rgb[i + 2] = fill.b;
    }
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  std::size_t index(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
  // Reading outside the image throws std::out_of_range; writing outside is clipped
  // silently, so drawing code never checks bounds itself.
  Rgb at(int x, int y) const {
    if (!inside(x, y))
      throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") outside " +
                              std::to_string(width) + "x" + std::to_string(height) + " image");
    const std::size_t i = index(x, y);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  void set(int x, int y, Rgb c) {
    if (!inside(x, y)) return;
    const std::size_t i = index(x, y);
    rgb[i] = c.r;
    rgb[i + 1] = c.g;
    rgb[i + 2] = c.b;
  }
};

}  // namespace gw
