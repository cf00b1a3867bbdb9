#pragma once
// Minimal PNG writer: 8-bit RGB, no interlace, filter type 0 on every row, one IDAT.
#include <cstdint>
#include <string>
#include <vector>

#include "apps/report/image.hpp"
#include "apps/report/zlib_deflate.hpp"

namespace gw {

// The PNG file bytes of `img` (signature, IHDR, IDAT, IEND; chunk CRCs included).
// Throws std::invalid_argument for an image whose pixel buffer does not match its size.
std::vector<std::uint8_t> encode_png(const Image& img, DeflateMode mode = DeflateMode::FixedHuffman);

// encode_png written atomically to `path`; ReportError "<path>: <problem>" on failure.
void write_png(const Image& img, const std::string& path, DeflateMode mode = DeflateMode::FixedHuffman);

}  // namespace gw
