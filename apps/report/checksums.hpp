#pragma once
// The two checksums a PNG needs: CRC-32 (ISO 3309, per chunk) and Adler-32 (zlib trailer).
#include <cstddef>
#include <cstdint>

namespace gw {

// CRC-32 of data[0..n), continuing from `crc` (start with 0). crc32("123456789") = 0xCBF43926.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0);

// Adler-32 of data[0..n), continuing from `adler` (start with 1). adler32("Wikipedia") = 0x11E60398.
std::uint32_t adler32(const std::uint8_t* data, std::size_t n, std::uint32_t adler = 1);

}  // namespace gw
