#include "casmap/io/deflate_stream.hpp"

// The match search (two layout distances and a hash table, greedy) that turns each segment of
// the input into symbols, and the zlib stream around the blocks deflate_block.cpp codes.

#if defined(CASMAP_HAVE_LIBDEFLATE)
#include <libdeflate.h>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "casmap/io/deflate_block.hpp"

namespace casmap::io::h5 {
namespace {

constexpr std::size_t kWindow = 32768;          // deflate's largest match distance
constexpr std::size_t kMinMatch = 4;            // compared as one 32-bit word
constexpr std::size_t kDefaultSegment = 65535;  // one stored block if incompressible
// Positions (+ 1; 0 = none) of the last occurrence of each hashed 4-byte word in the stream.
constexpr int kHashBits = 13;
using HashTable = std::array<std::uint32_t, std::size_t{1} << kHashBits>;

std::size_t Hash(std::uint32_t word) {
    return static_cast<std::size_t>((word * 2654435761U) >> (32 - kHashBits));
}

std::uint32_t Load32(const unsigned char* p) {
    std::uint32_t v = 0;
    std::memcpy(&v, p, sizeof(v));
    return v;
}

std::uint64_t Load64(const unsigned char* p) {
    std::uint64_t v = 0;
    std::memcpy(&v, p, sizeof(v));
    return v;
}

// Length of the common prefix of a and b (at most `limit`), the first kMinMatch bytes known
// equal. Overlapping ranges (b < a < b + 8) compare input with input, which is what the
// decoder's copy reproduces.
std::size_t MatchLength(const unsigned char* a, const unsigned char* b, std::size_t limit) {
    std::size_t k = kMinMatch;
    while (k + 8 <= limit) {
        const std::uint64_t x = Load64(a + k) ^ Load64(b + k);
        if (x != 0) {
            // Little-endian loads: the lowest differing byte is the first.
            return std::min(limit, k + static_cast<std::size_t>(std::countr_zero(x)) / 8);
        }
        k += 8;
    }
    while (k < limit && a[k] == b[k]) {
        ++k;
    }
    return k;
}

// Where one segment's match search looks: [begin, end) of `in`, the two layout distances
// (0 = not used) and the last position + 1 of each hashed 4-byte word (null = not used).
struct SegmentSearch {
    const unsigned char* in = nullptr;
    std::size_t begin = 0;
    std::size_t end = 0;
    std::size_t da = 0;
    std::size_t db = 0;
    std::uint32_t* table = nullptr;
};

// The symbols of the segment into `out_sym` (a literal byte, or kMatchFlag | (distance - 1) << 8
// | (length - 3)), counted in `codes`; returns how many. Matches: the longest of the two layout
// distances and the last position with the same hashed 4 bytes (greedy, no lazy evaluation).
std::size_t FindSymbols(const SegmentSearch& search, std::uint32_t* out_sym, BlockCodes& codes) {
    const unsigned char* const in = search.in;
    const std::size_t end = search.end;
    std::uint32_t* const table = search.table;
    std::size_t n = 0;
    for (std::size_t i = search.begin; i < end;) {
        std::size_t best = 0;
        std::size_t best_d = 0;
        if (i + kMinMatch <= end) {
            const std::size_t limit = std::min(kMaxMatch, end - i);
            const std::uint32_t here = Load32(in + i);
            const auto consider = [&](std::size_t d) {
                if (d != 0 && i >= d && Load32(in + i - d) == here) {
                    const std::size_t len = MatchLength(in + i, in + i - d, limit);
                    if (len > best) {
                        best = len;
                        best_d = d;
                    }
                }
            };
            consider(search.da);
            consider(search.db);
            if (table != nullptr) {
                std::uint32_t& slot = table[Hash(here)];
                const std::size_t hashed = slot != 0 ? i + 1 - slot : 0;
                slot = static_cast<std::uint32_t>(i + 1);
                consider(hashed <= kWindow ? hashed : 0);
            }
        }
        if (best >= kMinMatch) {
            out_sym[n++] = kMatchFlag | static_cast<std::uint32_t>((best_d - 1) << 8) |
                           static_cast<std::uint32_t>(best - 3);
            ++codes.ll_freq[kLength.symbol[best]];
            ++codes.d_freq[static_cast<std::size_t>(DistanceSymbol(best_d))];
            i += best;
        } else {
            out_sym[n++] = in[i];
            ++codes.ll_freq[in[i]];
            ++i;
        }
    }
    codes.ll_freq[kEndOfBlock] = 1;
    return n;
}

// One segment of the input: a dynamic Huffman block, or stored blocks when those are not
// larger (exact dynamic size against stored blocks' header + worst-case padding).
void Segment(const SegmentSearch& search,
             bool last,
             std::vector<std::uint32_t>& symbols,
             BitWriter& bits) {
    const std::size_t size = search.end - search.begin;
    symbols.resize(size);
    BlockCodes codes;
    const std::size_t n = FindSymbols(search, symbols.data(), codes);
    LiteralDistanceLengths(codes);
    HeaderRunLengths(codes);
    const std::uint64_t stored_bits =
        8 * static_cast<std::uint64_t>(size) + 42 * (size / kMaxStored + 1);
    if (DynamicBlockBits(codes) >= stored_bits) {
        StoredBlocks(search.in + search.begin, size, last, bits);
        return;
    }
    EmitDynamicBlock(codes, {symbols.data(), n}, last, bits);
}

}  // namespace

std::uint32_t Adler32(std::span<const unsigned char> data, std::uint32_t adler) {
#if defined(CASMAP_HAVE_LIBDEFLATE)
    return libdeflate_adler32(adler, data.data(), data.size());
#else
    constexpr std::uint32_t kMod = 65521;
    constexpr std::size_t kBlock = 5552;  // the most bytes before the sums can overflow
    std::uint32_t a = adler & 0xFFFFU;
    std::uint32_t b = adler >> 16;
    for (std::size_t first = 0; first < data.size(); first += kBlock) {
        const std::size_t last = std::min(data.size(), first + kBlock);
        for (std::size_t i = first; i < last; ++i) {
            a += data[i];
            b += a;
        }
        a %= kMod;
        b %= kMod;
    }
    return (b << 16) | a;
#endif
}

void DeflateZlib(std::span<const unsigned char> in,
                 const DeflateLayout& layout,
                 std::vector<unsigned char>& out) {
    const std::size_t segment = layout.segment_bytes == 0 ? kDefaultSegment : layout.segment_bytes;
    const std::size_t size = in.size();
    // Worst case: stored blocks throughout (at most 6 header bytes per 65535 and per segment; a
    // dynamic block is written only when smaller), plus the bit writer's 4-byte stores.
    out.resize(2 + size + 6 * (size / kMaxStored + size / segment + 2) + 4 + 16);
    out[0] = 0x78;  // deflate, 32 KiB window
    out[1] = 0x01;  // fastest; (0x78 * 256 + 0x01) % 31 == 0
    BitWriter bits(out.data() + 2);
    if (size == 0) {
        StoredBlocks(in.data(), 0, true, bits);
    } else {
        thread_local std::vector<std::uint32_t> symbols;
        thread_local HashTable head;
        head.fill(0);
        SegmentSearch search;
        search.in = in.data();
        search.da = layout.distance_a <= kWindow ? layout.distance_a : 0;
        search.db = layout.distance_b <= kWindow ? layout.distance_b : 0;
        search.table = layout.hashed ? head.data() : nullptr;
        for (std::size_t begin = 0; begin < size; begin += segment) {
            search.begin = begin;
            search.end = std::min(size, begin + segment);
            Segment(search, search.end == size, symbols, bits);
        }
    }
    bits.Align();
    const std::uint32_t adler = Adler32(in);
    unsigned char* tail = bits.position();
    for (int b = 3; b >= 0; --b) {
        *tail++ = static_cast<unsigned char>(adler >> (8 * b));
    }
    const auto length = static_cast<std::size_t>(tail - out.data());
    if (length > out.size()) {
        throw std::logic_error("DeflateZlib: output bound exceeded");
    }
    out.resize(length);
}

}  // namespace casmap::io::h5
