#include "apps/report/zlib_deflate.hpp"

#include <algorithm>

#include "apps/report/checksums.hpp"

namespace gw {
namespace {

// Deflate packs bits least-significant first; Huffman codes go most-significant first.
class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bits(std::uint32_t value, int n) {
    for (int i = 0; i < n; ++i) {
      acc_ |= ((value >> i) & 1u) << used_;
      if (++used_ == 8) flush_byte();
    }
  }
  void huffman(std::uint32_t code, int n) {  // code given MSB-first
    for (int i = n - 1; i >= 0; --i) bits((code >> i) & 1u, 1);
  }
  void align() {
    if (used_ > 0) flush_byte();
  }

 private:
  void flush_byte() {
    out_.push_back(static_cast<std::uint8_t>(acc_));
    acc_ = 0;
    used_ = 0;
  }
  std::vector<std::uint8_t>& out_;
  std::uint32_t acc_ = 0;
  int used_ = 0;
};

// RFC 1951 section 3.2.5 tables.
constexpr int kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr int kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr int kDistBase[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                               193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr int kDistExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

// RFC 1951 section 3.2.6: the fixed literal/length code.
void fixed_symbol(BitWriter& w, int s) {
  if (s < 144) w.huffman(0x30u + static_cast<std::uint32_t>(s), 8);
  else if (s < 256) w.huffman(0x190u + static_cast<std::uint32_t>(s - 144), 9);
  else if (s < 280) w.huffman(static_cast<std::uint32_t>(s - 256), 7);
  else w.huffman(0xC0u + static_cast<std::uint32_t>(s - 280), 8);
}

void fixed_match(BitWriter& w, int length, int distance) {
  int l = 28;
  while (kLengthBase[l] > length) --l;
  fixed_symbol(w, 257 + l);
  w.bits(static_cast<std::uint32_t>(length - kLengthBase[l]), kLengthExtra[l]);
  int d = 29;
  while (kDistBase[d] > distance) --d;
  w.huffman(static_cast<std::uint32_t>(d), 5);
  w.bits(static_cast<std::uint32_t>(distance - kDistBase[d]), kDistExtra[d]);
}

void deflate_stored(std::vector<std::uint8_t>& out, const std::uint8_t* data, std::size_t n) {
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(n - pos, 65535);
    const bool last = pos + len == n;
    out.push_back(last ? 1 : 0);  // BFINAL, BTYPE=00, then padding to the byte boundary
    out.push_back(static_cast<std::uint8_t>(len & 0xFF));
    out.push_back(static_cast<std::uint8_t>(len >> 8));
    out.push_back(static_cast<std::uint8_t>(~len & 0xFF));
    out.push_back(static_cast<std::uint8_t>((~len >> 8) & 0xFF));
    out.insert(out.end(), data + pos, data + pos + len);
    pos += len;
  } while (pos < n);
}

void deflate_fixed(std::vector<std::uint8_t>& out, const std::uint8_t* data, std::size_t n) {
  constexpr int kWindow = 32768, kMinMatch = 3, kMaxMatch = 258, kMaxChain = 48;
  constexpr int kHashBits = 15;
  constexpr std::uint32_t kHashMask = (1u << kHashBits) - 1;
  std::vector<int> head(std::size_t{1} << kHashBits, -1);
  std::vector<int> prev(kWindow, -1);
  auto hash = [&](std::size_t i) {
    const std::uint32_t v = (std::uint32_t{data[i]} << 16) | (std::uint32_t{data[i + 1]} << 8) | data[i + 2];
    return (v * 2654435761u) >> (32 - kHashBits) & kHashMask;
  };
  auto insert = [&](std::size_t i) {
    if (i + kMinMatch > n) return;
    const std::uint32_t h = hash(i);
    prev[i % kWindow] = head[h];
    head[h] = static_cast<int>(i);
  };

  BitWriter w(out);
  w.bits(1, 1);  // BFINAL: one block
  w.bits(1, 2);  // BTYPE = 01, fixed Huffman
  std::size_t i = 0;
  while (i < n) {
    int best_len = 0, best_dist = 0;
    if (i + kMinMatch <= n) {
      const int max_len = static_cast<int>(std::min<std::size_t>(kMaxMatch, n - i));
      int candidate = head[hash(i)];
      for (int chain = 0; candidate >= 0 && chain < kMaxChain; ++chain) {
        const std::size_t dist = i - static_cast<std::size_t>(candidate);
        if (dist > static_cast<std::size_t>(kWindow)) break;
        int len = 0;
        const std::uint8_t* a = data + candidate;
        const std::uint8_t* b = data + i;
        while (len < max_len && a[len] == b[len]) ++len;
        if (len > best_len) {
          best_len = len;
          best_dist = static_cast<int>(dist);
          if (len == max_len) break;
        }
        const int next = prev[static_cast<std::size_t>(candidate) % kWindow];
        if (next >= candidate) break;  // slot reused by a newer position: chain ends
        candidate = next;
      }
    }
    if (best_len >= kMinMatch) {
      fixed_match(w, best_len, best_dist);
      for (int k = 0; k < best_len; ++k) insert(i + static_cast<std::size_t>(k));
      i += static_cast<std::size_t>(best_len);
    } else {
      fixed_symbol(w, data[i]);
      insert(i);
      ++i;
    }
  }
  fixed_symbol(w, 256);  // end of block
  w.align();
}

}  // namespace

std::vector<std::uint8_t> zlib_compress(const std::uint8_t* data, std::size_t n, DeflateMode mode) {
  std::vector<std::uint8_t> out;
  out.reserve(mode == DeflateMode::Stored ? n + n / 65535 * 5 + 16 : n / 8 + 64);
  out.push_back(0x78);  // CMF: deflate, 32 KiB window
  out.push_back(0x01);  // FLG: no dictionary, check bits make 0x7801 a multiple of 31
  if (mode == DeflateMode::Stored) deflate_stored(out, data, n);
  else deflate_fixed(out, data, n);
  const std::uint32_t a = adler32(data, n);
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(a >> s));
  return out;
}

}  // namespace gw
