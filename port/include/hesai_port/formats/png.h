// A small PNG encoder without zlib: 8-bit RGB images, deflate done here.
//
// PNG (ISO/IEC 15948, W3C PNG 2nd ed.) stores its pixels as a zlib stream (RFC 1950) of deflate
// data (RFC 1951). Two deflate modes are offered: stored blocks (no compression, simplest) and
// one fixed-Huffman block with greedy LZ77 matching (a dark bird's-eye view shrinks ~20x).
// Each row gets the PNG filter (None, Sub, Up, Average, Paeth) with the smallest sum of
// absolute values, the heuristic the PNG specification suggests (section 12.8).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hesai {
namespace port {

/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel (R, G, B).
struct RgbImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes

  RgbImage() = default;
  /// A width x height image filled with one colour.
  RgbImage(std::uint32_t w, std::uint32_t h, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0);

  /// Pointer to pixel (x, y); the caller has checked x < width and y < height.
  std::uint8_t* at(std::uint32_t x, std::uint32_t y) {
    return rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
  }
  const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const {
    return rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
  }
};

/// How the pixel data is deflated.
enum class PngDeflate : std::uint8_t {
  stored,         ///< stored (uncompressed) deflate blocks of at most 65535 bytes
  fixed_huffman,  ///< one deflate block with the fixed Huffman codes and LZ77 back-references
};

/// CRC-32 of PNG chunks and zlib/gzip (reflected, polynomial 0xEDB88320, init and final xor
/// 0xFFFFFFFF). Not the MPEG-2 CRC of the core. Chain calls by passing the previous result.
std::uint32_t png_crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

/// Adler-32 of RFC 1950 (the zlib stream's trailer). Chain calls by passing the previous result.
std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t adler = 1);

/// The zlib stream (RFC 1950: CMF 0x78, FLG, deflate data, big-endian Adler-32) of `data`.
std::vector<std::uint8_t> zlib_compress(const std::uint8_t* data, std::size_t size, PngDeflate mode);

/// The whole PNG file of `image`: signature, IHDR (8-bit truecolour, no interlace), IDAT chunks
/// of at most 256 KiB, IEND. Empty when the image is empty or its size does not match width/height.
std::vector<std::uint8_t> encode_png(const RgbImage& image, PngDeflate mode = PngDeflate::fixed_huffman);

}  // namespace port
}  // namespace hesai
