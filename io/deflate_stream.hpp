#pragma once

// A fast zlib stream encoder (RFC 1950 around RFC 1951 deflate) for the chunks of run-file
// datasets: what HDF5's deflate filter stores and every HDF5 reader (zlib's inflate) decodes.
// It trades the general match search of zlib or libdeflate for the repeats these arrays have:
// each position is compared with the bytes at two fixed distances (the previous element or byte,
// the same element of the previous row) and at the last position with the same 4 bytes; matches of
// 4 to 258 bytes are Huffman-coded in one dynamic block per segment, and a segment that does not
// get smaller is stored as is.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace casmap::io::h5 {

/// Where the encoder looks for repeats in one input (all sizes in bytes).
struct DeflateLayout {
    /// Blocks start at multiples of this (a byte plane of a shuffled chunk, so each plane gets
    /// its own Huffman code); 0 = segments of 65535 bytes.
    std::size_t segment_bytes = 0;
    /// The two match distances tried at every position (1 .. 32768; 0 = not used).
    std::size_t distance_a = 1;
    std::size_t distance_b = 0;
    /// Also try the last position with the same 4 bytes (a hash table): finds repeats at other
    /// distances, at some cost in speed.
    bool hashed = true;
};

/// Writes the zlib stream of `in` into `out` (resized to the stream's length). Deterministic:
/// the same input and layout give the same bytes.
void DeflateZlib(std::span<const unsigned char> in,
                 const DeflateLayout& layout,
                 std::vector<unsigned char>& out);

/// Adler-32 of `data` (RFC 1950), starting from `adler` (1 for a new stream).
[[nodiscard]] std::uint32_t Adler32(std::span<const unsigned char> data, std::uint32_t adler = 1);

}  // namespace casmap::io::h5
