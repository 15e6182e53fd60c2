// PNG encoder: filters (PNG spec section 9), zlib stream (RFC 1950), deflate (RFC 1951).
#include "hesai_port/formats/png.h"

#include <array>
#include <cstdlib>
#include <cstring>

#include "hesai_port/base/crc32_ieee.h"

namespace hesai {
namespace port {
namespace {

// ---- big-endian fields (the chunks' CRC-32: png_crc32(), hesai_port/base/crc32_ieee.h) ----

void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

// ---- Deflate: stored blocks ----

void deflate_stored(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& out) {
  std::size_t off = 0;
  do {
    const std::size_t n = (size - off < 65535u) ? size - off : 65535u;
    const bool final_block = (n == size - off);
    out.push_back(final_block ? 1 : 0);  // BFINAL, BTYPE = 00, then pad to the byte boundary
    const auto len = static_cast<std::uint16_t>(n);
    const auto nlen = static_cast<std::uint16_t>(~len);
    out.push_back(static_cast<std::uint8_t>(len));
    out.push_back(static_cast<std::uint8_t>(len >> 8));
    out.push_back(static_cast<std::uint8_t>(nlen));
    out.push_back(static_cast<std::uint8_t>(nlen >> 8));
    out.insert(out.end(), data + off, data + off + n);
    off += n;
  } while (off < size);
}

// ---- Deflate: one fixed-Huffman block (RFC 1951 section 3.2.6) ----

// Writes bits least significant first, as deflate packs them.
class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bits(std::uint32_t value, unsigned count) {
    acc_ |= static_cast<std::uint64_t>(value) << used_;
    used_ += count;
    while (used_ >= 8) {
      out_.push_back(static_cast<std::uint8_t>(acc_));
      acc_ >>= 8;
      used_ -= 8;
    }
  }
  void flush() {
    if (used_ > 0) out_.push_back(static_cast<std::uint8_t>(acc_));
    acc_ = 0;
    used_ = 0;
  }

 private:
  std::vector<std::uint8_t>& out_;
  std::uint64_t acc_ = 0;
  unsigned used_ = 0;
};

// A Huffman code ready to write LSB-first: bit-reversed code and its length.
struct Code {
  std::uint16_t bits = 0;
  std::uint8_t length = 0;
};

constexpr std::uint16_t reverse_bits(std::uint32_t v, unsigned n) {
  std::uint32_t r = 0;
  for (unsigned i = 0; i < n; ++i) r |= ((v >> i) & 1u) << (n - 1 - i);
  return static_cast<std::uint16_t>(r);
}

// Fixed literal/length code: 0-143 8 bits from 0x30, 144-255 9 bits from 0x190, 256-279 7 bits
// from 0, 280-287 8 bits from 0xC0.
constexpr std::array<Code, 288> make_fixed_litlen() {
  std::array<Code, 288> t{};
  for (std::uint32_t s = 0; s < 288; ++s) {
    std::uint32_t code = 0;
    unsigned len = 0;
    if (s <= 143) { code = 0x30 + s; len = 8; }
    else if (s <= 255) { code = 0x190 + (s - 144); len = 9; }
    else if (s <= 279) { code = s - 256; len = 7; }
    else { code = 0xC0 + (s - 280); len = 8; }
    t[s] = Code{reverse_bits(code, len), static_cast<std::uint8_t>(len)};
  }
  return t;
}
constexpr std::array<Code, 288> kFixedLitLen = make_fixed_litlen();
static_assert(kFixedLitLen[0].length == 8 && kFixedLitLen[256].length == 7 && kFixedLitLen[144].length == 9);

// Length codes 257..285: base length and extra bits (RFC 1951 section 3.2.5).
constexpr std::array<std::uint16_t, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,
                                                       15, 17, 19, 23, 27, 31, 35, 43, 51,  59,
                                                       67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                       2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
// Distance codes 0..29.
constexpr std::array<std::uint16_t, 30> kDistBase = {1,    2,    3,    4,    5,    7,     9,     13,
                                                     17,   25,   33,   49,   65,   97,    129,   193,
                                                     257,  385,  513,  769,  1025, 1537,  2049,  3073,
                                                     4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<std::uint8_t, 30> kDistExtra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                     6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
static_assert(kLengthBase[27] + (1u << kLengthExtra[27]) - 1 == 258, "length table adds up");
static_assert(kDistBase[29] + (1u << kDistExtra[29]) - 1 == 32768, "distance table adds up");

constexpr std::size_t kMinMatch = 3;
constexpr std::size_t kMaxMatch = 258;
constexpr std::size_t kWindow = 32768;
constexpr unsigned kHashBits = 15;

std::uint32_t hash3(const std::uint8_t* p) {
  const std::uint32_t v = static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
                          (static_cast<std::uint32_t>(p[2]) << 16);
  return (v * 2654435761u) >> (32 - kHashBits);
}

void put_match(BitWriter& bw, std::size_t length, std::size_t distance) {
  std::size_t lc = kLengthBase.size() - 1;
  while (kLengthBase[lc] > length) --lc;
  const Code& c = kFixedLitLen[257 + lc];
  bw.bits(c.bits, c.length);
  if (kLengthExtra[lc] != 0) bw.bits(static_cast<std::uint32_t>(length - kLengthBase[lc]), kLengthExtra[lc]);
  std::size_t dc = kDistBase.size() - 1;
  while (kDistBase[dc] > distance) --dc;
  bw.bits(reverse_bits(static_cast<std::uint32_t>(dc), 5), 5);
  if (kDistExtra[dc] != 0) bw.bits(static_cast<std::uint32_t>(distance - kDistBase[dc]), kDistExtra[dc]);
}

// Greedy LZ77 with one candidate per 3-byte hash (the most recent position).
void deflate_fixed(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& out) {
  BitWriter bw(out);
  bw.bits(1, 1);  // BFINAL
  bw.bits(1, 2);  // BTYPE = 01, fixed Huffman codes
  std::vector<std::int64_t> head(std::size_t{1} << kHashBits, -1);
  std::size_t p = 0;
  while (p < size) {
    std::size_t best_len = 0;
    std::size_t best_dist = 0;
    if (size - p >= kMinMatch) {
      const std::uint32_t h = hash3(data + p);
      const std::int64_t cand = head[h];
      head[h] = static_cast<std::int64_t>(p);
      if (cand >= 0 && p - static_cast<std::size_t>(cand) <= kWindow) {
        const auto c = static_cast<std::size_t>(cand);
        const std::size_t limit = (size - p < kMaxMatch) ? size - p : kMaxMatch;
        std::size_t n = 0;
        while (n < limit && data[c + n] == data[p + n]) ++n;
        if (n >= kMinMatch) {
          best_len = n;
          best_dist = p - c;
        }
      }
    }
    if (best_len == 0) {
      const Code& c = kFixedLitLen[data[p]];
      bw.bits(c.bits, c.length);
      ++p;
      continue;
    }
    put_match(bw, best_len, best_dist);
    // Index the positions the match covers so later data can refer to them.
    const std::size_t end = p + best_len;
    for (++p; p < end; ++p) {
      if (size - p >= kMinMatch) head[hash3(data + p)] = static_cast<std::int64_t>(p);
    }
  }
  const Code& eob = kFixedLitLen[256];
  bw.bits(eob.bits, eob.length);
  bw.flush();
}

// ---- PNG filters ----

std::uint8_t paeth(std::uint8_t a, std::uint8_t b, std::uint8_t c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a);
  const int pb = std::abs(p - b);
  const int pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  if (pb <= pc) return b;
  return c;
}

// Filters `row` (with `prev`, the unfiltered row above, or zeros) by filter type `type` into `out`.
void filter_row(int type, const std::uint8_t* row, const std::uint8_t* prev, std::size_t n, std::size_t bpp,
                std::uint8_t* out) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t a = i >= bpp ? row[i - bpp] : 0;
    const std::uint8_t b = prev[i];
    const std::uint8_t c = i >= bpp ? prev[i - bpp] : 0;
    std::uint8_t pred = 0;
    switch (type) {
      case 1: pred = a; break;
      case 2: pred = b; break;
      case 3: pred = static_cast<std::uint8_t>((a + b) / 2); break;
      case 4: pred = paeth(a, b, c); break;
      default: break;
    }
    out[i] = static_cast<std::uint8_t>(row[i] - pred);
  }
}

std::size_t abs_sum(const std::uint8_t* v, std::size_t n) {
  std::size_t s = 0;
  for (std::size_t i = 0; i < n; ++i) s += v[i] < 128 ? v[i] : 256u - v[i];
  return s;
}

void append_chunk(std::vector<std::uint8_t>& png, const char type[4], const std::uint8_t* data, std::size_t n) {
  put_be32(png, static_cast<std::uint32_t>(n));
  const std::size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  if (n != 0) png.insert(png.end(), data, data + n);
  put_be32(png, png_crc32(png.data() + start, 4 + n));
}

}  // namespace

RgbImage::RgbImage(std::uint32_t w, std::uint32_t h, std::uint8_t r, std::uint8_t g, std::uint8_t b)
    : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  }
}

std::uint32_t png_crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  return crc32_ieee(data, size, crc);
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t adler) {
  constexpr std::uint32_t kMod = 65521;
  std::uint32_t a = adler & 0xFFFFu;
  std::uint32_t b = adler >> 16;
  while (size > 0) {
    // 5552 bytes is the most that can be summed before b could overflow 32 bits (zlib's NMAX).
    const std::size_t n = size < 5552 ? size : 5552;
    for (std::size_t i = 0; i < n; ++i) {
      a += data[i];
      b += a;
    }
    a %= kMod;
    b %= kMod;
    data += n;
    size -= n;
  }
  return (b << 16) | a;
}

std::vector<std::uint8_t> zlib_compress(const std::uint8_t* data, std::size_t size, PngDeflate mode) {
  std::vector<std::uint8_t> out;
  out.reserve(mode == PngDeflate::stored ? size + size / 65535 * 5 + 16 : size / 4 + 64);
  // CMF 0x78: deflate, 32 KiB window. FLG 0x01: no dictionary, "fastest" level, and
  // (0x78 * 256 + 0x01) is a multiple of 31 as RFC 1950 requires.
  static_assert((0x78 * 256 + 0x01) % 31 == 0, "zlib header check bits");
  out.push_back(0x78);
  out.push_back(0x01);
  if (mode == PngDeflate::stored) {
    deflate_stored(data, size, out);
  } else {
    deflate_fixed(data, size, out);
  }
  put_be32(out, adler32(data, size));
  return out;
}

std::vector<std::uint8_t> encode_png(const RgbImage& image, PngDeflate mode) {
  std::vector<std::uint8_t> png;
  const std::size_t w = image.width;
  const std::size_t h = image.height;
  if (w == 0 || h == 0 || w > 0x7FFFFFFFu || h > 0x7FFFFFFFu) return png;
  if (w > (static_cast<std::size_t>(-1) / 3 - 1) / h || image.rgb.size() != w * h * 3) return png;

  // Filtered scanlines: one filter-type byte, then the row's filtered bytes.
  const std::size_t stride = w * 3;
  std::vector<std::uint8_t> raw((stride + 1) * h);
  std::vector<std::uint8_t> zeros(stride, 0);
  std::array<std::vector<std::uint8_t>, 5> trial;
  for (auto& t : trial) t.resize(stride);
  for (std::size_t y = 0; y < h; ++y) {
    const std::uint8_t* row = image.rgb.data() + y * stride;
    const std::uint8_t* prev = y == 0 ? zeros.data() : row - stride;
    int best = 0;
    std::size_t best_sum = static_cast<std::size_t>(-1);
    for (int f = 0; f < 5; ++f) {
      auto& t = trial[static_cast<std::size_t>(f)];
      filter_row(f, row, prev, stride, 3, t.data());
      const std::size_t s = abs_sum(t.data(), stride);
      if (s < best_sum) {
        best_sum = s;
        best = f;
      }
    }
    std::uint8_t* dst = raw.data() + y * (stride + 1);
    dst[0] = static_cast<std::uint8_t>(best);
    std::memcpy(dst + 1, trial[static_cast<std::size_t>(best)].data(), stride);
  }
  const std::vector<std::uint8_t> z = zlib_compress(raw.data(), raw.size(), mode);

  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  png.reserve(z.size() + 128);
  png.insert(png.end(), kSignature, kSignature + 8);
  std::vector<std::uint8_t> ihdr;
  put_be32(ihdr, static_cast<std::uint32_t>(w));
  put_be32(ihdr, static_cast<std::uint32_t>(h));
  ihdr.push_back(8);  // bit depth
  ihdr.push_back(2);  // colour type 2: truecolour (RGB)
  ihdr.push_back(0);  // compression method 0: deflate
  ihdr.push_back(0);  // filter method 0: adaptive, five filter types
  ihdr.push_back(0);  // no interlace
  append_chunk(png, "IHDR", ihdr.data(), ihdr.size());
  constexpr std::size_t kIdatMax = 256 * 1024;
  for (std::size_t off = 0; off < z.size(); off += kIdatMax) {
    const std::size_t n = z.size() - off < kIdatMax ? z.size() - off : kIdatMax;
    append_chunk(png, "IDAT", z.data() + off, n);
  }
  append_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace port
}  // namespace hesai
