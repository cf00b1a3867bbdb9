#pragma once
// PNG files through libpng: 8-bit RGB, no interlace, libpng's default filters and zlib level.
#include <cstdint>
#include <string>
#include <vector>

#include "lib/report/image.hpp"

namespace gw {

// The PNG file bytes of `img`. Throws std::invalid_argument for an image whose pixel buffer does
// not match its size, std::runtime_error when libpng reports an error.
std::vector<std::uint8_t> encode_png(const Image& img);

// encode_png written atomically to `path`; ReportError "<path>: <problem>" on failure.
void write_png(const Image& img, const std::string& path);

}  // namespace gw
