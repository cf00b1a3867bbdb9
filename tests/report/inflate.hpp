#pragma once
// A tiny, independent zlib/deflate decoder for the tests: stored and fixed-Huffman blocks
// (what our encoder writes); dynamic-Huffman blocks are reported, not decoded.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gw::test {

class BitReader {
 public:
  BitReader(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  unsigned bit() {
    if (pos_ >= n_) throw std::runtime_error("inflate: ran out of data");
    const unsigned b = (d_[pos_] >> bit_) & 1u;
    if (++bit_ == 8) {
      bit_ = 0;
      ++pos_;
    }
    return b;
  }
  unsigned bits(int k) {  // LSB first
    unsigned v = 0;
    for (int i = 0; i < k; ++i) v |= bit() << i;
    return v;
  }
  unsigned huffman(int k) {  // MSB first
    unsigned v = 0;
    for (int i = 0; i < k; ++i) v = (v << 1) | bit();
    return v;
  }
  void align() {
    if (bit_) {
      bit_ = 0;
      ++pos_;
    }
  }
  std::uint8_t byte() {
    if (pos_ >= n_) throw std::runtime_error("inflate: ran out of data");
    return d_[pos_++];
  }
  std::size_t position() const { return pos_; }

 private:
  const std::uint8_t* d_;
  std::size_t n_, pos_ = 0;
  int bit_ = 0;
};

// RFC 1951 3.2.6, decoded bit by bit.
inline int fixed_literal(BitReader& r) {
  unsigned v = r.huffman(7);
  if (v <= 23) return 256 + static_cast<int>(v);
  v = (v << 1) | r.bit();
  if (v >= 0x30 && v <= 0xBF) return static_cast<int>(v - 0x30);
  if (v >= 0xC0 && v <= 0xC7) return 280 + static_cast<int>(v - 0xC0);
  v = (v << 1) | r.bit();
  if (v >= 0x190 && v <= 0x1FF) return 144 + static_cast<int>(v - 0x190);
  throw std::runtime_error("inflate: bad fixed code");
}

struct Inflated {
  std::vector<std::uint8_t> data;
  std::uint32_t adler_trailer = 0;
  int stored_blocks = 0, fixed_blocks = 0;
};

// Decodes a zlib stream; throws on a bad header, a dynamic block or corrupt data.
inline Inflated zlib_inflate(const std::vector<std::uint8_t>& z) {
  static const int len_base[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27,
                                   31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
  static const int len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
  static const int dist_base[30] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769,
                                    1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
  static const int dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8,
                                     9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
  if (z.size() < 6) throw std::runtime_error("zlib: too short");
  if ((z[0] & 0x0F) != 8 || ((z[0] << 8) | z[1]) % 31 != 0 || (z[1] & 0x20))
    throw std::runtime_error("zlib: bad header");
  Inflated out;
  BitReader r(z.data() + 2, z.size() - 6);
  bool last = false;
  while (!last) {
    last = r.bits(1) != 0;
    const unsigned type = r.bits(2);
    if (type == 0) {
      ++out.stored_blocks;
      r.align();
      // One read per statement: the operands of | are evaluated in unspecified order.
      unsigned len = r.byte();
      len |= static_cast<unsigned>(r.byte()) << 8;
      unsigned nlen = r.byte();
      nlen |= static_cast<unsigned>(r.byte()) << 8;
      if ((len ^ 0xFFFFu) != nlen) throw std::runtime_error("zlib: stored LEN/NLEN mismatch");
      for (unsigned i = 0; i < len; ++i) out.data.push_back(r.byte());
    } else if (type == 1) {
      ++out.fixed_blocks;
      for (;;) {
        const int s = fixed_literal(r);
        if (s < 256) {
          out.data.push_back(static_cast<std::uint8_t>(s));
          continue;
        }
        if (s == 256) break;
        if (s > 285) throw std::runtime_error("zlib: bad length symbol");
        const int length = len_base[s - 257] + static_cast<int>(r.bits(len_extra[s - 257]));
        const unsigned d = r.huffman(5);
        if (d > 29) throw std::runtime_error("zlib: bad distance symbol");
        const std::size_t dist = static_cast<std::size_t>(dist_base[d]) + r.bits(dist_extra[d]);
        if (dist > out.data.size()) throw std::runtime_error("zlib: distance beyond start");
        for (int k = 0; k < length; ++k) out.data.push_back(out.data[out.data.size() - dist]);
      }
    } else {
      throw std::runtime_error("zlib: block type " + std::to_string(type) + " not supported by the test decoder");
    }
  }
  r.align();
  if (2 + r.position() != z.size() - 4) throw std::runtime_error("zlib: trailing bytes after the last block");
  const std::size_t t = z.size() - 4;
  out.adler_trailer = (std::uint32_t{z[t]} << 24) | (std::uint32_t{z[t + 1]} << 16) | (std::uint32_t{z[t + 2]} << 8) | z[t + 3];
  return out;
}

}  // namespace gw::test
