#pragma once
// A small zlib (RFC 1950) / deflate (RFC 1951) compressor for the PNG encoder: either
// stored blocks (no compression) or LZ77 with the fixed Huffman code. Flat-colour
// figures shrink ~50-100x with the latter; no dynamic Huffman tables are needed for that.
#include <cstdint>
#include <vector>

namespace gw {

enum class DeflateMode { Stored, FixedHuffman };

// A complete zlib stream (2-byte header, deflate blocks, big-endian Adler-32) of data[0..n).
std::vector<std::uint8_t> zlib_compress(const std::uint8_t* data, std::size_t n,
                                        DeflateMode mode = DeflateMode::FixedHuffman);

}  // namespace gw
