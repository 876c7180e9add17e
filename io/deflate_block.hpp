#pragma once

// One deflate block from the symbols of DeflateZlib's match search (deflate_stream.cpp):
// Huffman code lengths and canonical codes, the dynamic block header, its exact size, and the
// bit packing (RFC 1951), or the input as stored blocks. Private to io.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>

namespace casmap::io::h5 {

inline constexpr std::size_t kMaxMatch = 258;
inline constexpr std::size_t kMaxStored = 65535;  // bytes of one stored block
inline constexpr int kLitLen = 286;  // literal/length alphabet (0-255, end 256, 257-285)
inline constexpr int kDist = 30;
inline constexpr int kCodeLen = 19;
inline constexpr int kEndOfBlock = 256;
// A symbol of the match search: a literal byte, or kMatchFlag | (distance - 1) << 8 |
// (length - 3).
inline constexpr std::uint32_t kMatchFlag = 1U << 31;
inline constexpr std::array<int, kDist> kDistBase = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};

// Length 3..258 -> literal/length symbol, its extra bits and their value (RFC 1951 3.2.5).
struct LengthCodes {
    std::array<std::uint16_t, kMaxMatch + 1> symbol{};
    std::array<std::uint8_t, kMaxMatch + 1> extra_bits{};
    std::array<std::uint8_t, kMaxMatch + 1> extra{};
};

constexpr LengthCodes MakeLengthCodes() {
    constexpr std::array<int, 29> base = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                          15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                          67, 83, 99, 115, 131, 163, 195, 227, 258};
    constexpr std::array<int, 29> bits = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                          2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    LengthCodes t;
    for (std::size_t c = 0; c < 28; ++c) {  // 258 has its own symbol 285, not 284 + 31
        for (int len = base[c]; len < base[c] + (1 << bits[c]) && len < 258; ++len) {
            t.symbol[static_cast<std::size_t>(len)] = static_cast<std::uint16_t>(257 + c);
            t.extra_bits[static_cast<std::size_t>(len)] = static_cast<std::uint8_t>(bits[c]);
            t.extra[static_cast<std::size_t>(len)] = static_cast<std::uint8_t>(len - base[c]);
        }
    }
    t.symbol[258] = 285;
    return t;
}
inline constexpr LengthCodes kLength = MakeLengthCodes();

// Distance 1..32768 -> distance symbol: d - 1 < 256 at [d - 1], else at [256 + (d - 1) / 128].
constexpr std::array<std::uint8_t, 512> MakeDistanceCodes() {
    std::array<std::uint8_t, 512> t{};
    for (std::size_t c = 0; c < kDist; ++c) {
        const int bits = c < 4 ? 0 : static_cast<int>(c) / 2 - 1;
        for (int d = kDistBase[c]; d < kDistBase[c] + (1 << bits); ++d) {
            const auto k = static_cast<std::size_t>(d - 1);
            t[k < 256 ? k : 256 + (k >> 7)] = static_cast<std::uint8_t>(c);
        }
    }
    return t;
}
inline constexpr std::array<std::uint8_t, 512> kDistCode = MakeDistanceCodes();

inline int DistanceSymbol(std::size_t d) {
    const std::size_t k = d - 1;
    return kDistCode[k < 256 ? k : 256 + (k >> 7)];
}

// Bits written least significant first, as deflate packs them.
class BitWriter {
public:
    explicit BitWriter(unsigned char* out) : out_(out) {}
    void Put(std::uint64_t bits, int count) {  // count <= 32
        buffer_ |= bits << count_;
        count_ += count;
        if (count_ >= 32) {
            for (int b = 0; b < 4; ++b) {
                out_[b] = static_cast<unsigned char>(buffer_ >> (8 * b));
            }
            out_ += 4;
            buffer_ >>= 32;
            count_ -= 32;
        }
    }
    // Pads with zero bits to the next byte boundary and flushes.
    void Align() {
        for (; count_ > 0; count_ -= 8) {
            *out_++ = static_cast<unsigned char>(buffer_);
            buffer_ >>= 8;
        }
        count_ = 0;
        buffer_ = 0;
    }
    // Raw bytes after Align().
    void Bytes(const unsigned char* data, std::size_t size) {
        if (size > 0) {  // an empty input's data() may be null: no memcpy from it
            std::memcpy(out_, data, size);
            out_ += size;
        }
    }
    [[nodiscard]] unsigned char* position() const { return out_; }

private:
    unsigned char* out_;
    std::uint64_t buffer_ = 0;
    int count_ = 0;
};

// One dynamic block's symbol counts, Huffman code lengths and run-length coded header.
struct BlockCodes {
    std::array<std::uint32_t, kLitLen> ll_freq{};
    std::array<std::uint32_t, kDist> d_freq{};
    std::array<std::uint8_t, kLitLen> ll_len{};
    std::array<std::uint8_t, kDist> d_len{};
    int hlit = kLitLen;
    int hdist = kDist;
    std::array<std::pair<std::uint8_t, std::uint8_t>, kLitLen + kDist> rle{};  // symbol, extra
    int n_rle = 0;
    std::array<std::uint32_t, kCodeLen> cl_freq{};
    std::array<std::uint8_t, kCodeLen> cl_len{};
    int hclen = kCodeLen;
};

/// Writes `data` as stored blocks of at most kMaxStored bytes (the last one final if `last`).
void StoredBlocks(const unsigned char* data, std::size_t size, bool last, BitWriter& bits);
/// Huffman code lengths of both alphabets from `codes`' counts, and how many the header lists.
void LiteralDistanceLengths(BlockCodes& codes);
/// The run-length coded code lengths and the code-length code (after LiteralDistanceLengths).
void HeaderRunLengths(BlockCodes& codes);
/// Exact size in bits of the dynamic block (header, symbols, extra bits).
[[nodiscard]] std::uint64_t DynamicBlockBits(const BlockCodes& codes);
/// Writes the dynamic block: header, `symbols` (the match search's encoding), end of block.
void EmitDynamicBlock(const BlockCodes& codes,
                      std::span<const std::uint32_t> symbols,
                      bool last,
                      BitWriter& bits);

}  // namespace casmap::io::h5
