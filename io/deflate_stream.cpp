#include "casmap/io/deflate_stream.hpp"

#if defined(CASMAP_HAVE_LIBDEFLATE)
#include <libdeflate.h>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace casmap::io::h5 {
namespace {

constexpr std::size_t kWindow = 32768;  // deflate's largest match distance
constexpr std::size_t kMinMatch = 4;    // compared as one 32-bit word
constexpr std::size_t kMaxMatch = 258;
constexpr std::size_t kDefaultSegment = 65535;  // one stored block if incompressible
constexpr std::size_t kMaxStored = 65535;       // bytes of one stored block
constexpr int kLitLen = 286;                    // literal/length alphabet (0-255, end 256, 257-285)
constexpr int kDist = 30;
constexpr int kCodeLen = 19;
constexpr int kEndOfBlock = 256;
constexpr std::uint32_t kMatchFlag = 1U << 31;
// The order in which a dynamic block header lists the code-length code's lengths.
constexpr std::array<int, kCodeLen> kCodeLenOrder = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                     11, 4,  12, 3, 13, 2, 14, 1, 15};
constexpr std::array<int, kDist> kDistBase = {
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
constexpr LengthCodes kLength = MakeLengthCodes();

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
constexpr std::array<std::uint8_t, 512> kDistCode = MakeDistanceCodes();

int DistanceSymbol(std::size_t d) {
    const std::size_t k = d - 1;
    return kDistCode[k < 256 ? k : 256 + (k >> 7)];
}

int DistanceExtraBits(int symbol) { return symbol < 4 ? 0 : symbol / 2 - 1; }

// Positions (+ 1; 0 = none) of the last occurrence of each hashed 4-byte word in the stream.
constexpr int kHashBits = 13;
using HashTable = std::array<std::uint32_t, std::size_t{1} << kHashBits>;

std::size_t Hash(std::uint32_t word) {
    return static_cast<std::size_t>((word * 2654435761U) >> (32 - kHashBits));
}

int LengthExtraBits(int symbol) {  // for symbols 257..285
    return symbol < 265 || symbol == 285 ? 0 : (symbol - 261) / 4;
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

// Lengths (<= max_length) of a Huffman code for freq[0..n); unused symbols get 0, except that
// at least two symbols get a code, so the code is always complete (every inflate accepts it).
// Huffman's tree from the sorted frequencies (two queues), then lengths beyond the limit are
// folded back keeping the Kraft sum exact (as miniz does), and handed out by frequency.
void HuffmanLengths(const std::uint32_t* freq, int n, int max_length, std::uint8_t* lengths) {
    std::array<std::pair<std::uint32_t, int>, kLitLen> leaves{};
    int m = 0;
    for (int s = 0; s < n; ++s) {
        lengths[s] = 0;
        if (freq[s] != 0) {
            leaves[static_cast<std::size_t>(m++)] = {freq[s], s};
        }
    }
    for (int s = 0; s < n && m < 2; ++s) {
        if (freq[s] == 0) {
            leaves[static_cast<std::size_t>(m++)] = {0U, s};
        }
    }
    std::sort(leaves.begin(), leaves.begin() + m);
    std::array<std::uint64_t, 2 * kLitLen> weight{};
    std::array<int, 2 * kLitLen> parent{};
    for (int i = 0; i < m; ++i) {
        weight[static_cast<std::size_t>(i)] = leaves[static_cast<std::size_t>(i)].first;
    }
    int leaf = 0;
    int inner = m;
    for (int next = m; next < 2 * m - 1; ++next) {
        const auto take = [&]() {
            if (leaf < m && (inner >= next || weight[static_cast<std::size_t>(leaf)] <=
                                                  weight[static_cast<std::size_t>(inner)])) {
                return leaf++;
            }
            return inner++;
        };
        const int a = take();
        const int b = take();
        weight[static_cast<std::size_t>(next)] =
            weight[static_cast<std::size_t>(a)] + weight[static_cast<std::size_t>(b)];
        parent[static_cast<std::size_t>(a)] = next;
        parent[static_cast<std::size_t>(b)] = next;
    }
    std::array<int, 2 * kLitLen> depth{};
    for (int k = 2 * m - 3; k >= 0; --k) {
        depth[static_cast<std::size_t>(k)] =
            depth[static_cast<std::size_t>(parent[static_cast<std::size_t>(k)])] + 1;
    }
    std::array<std::uint32_t, kLitLen + 1> count{};
    for (int i = 0; i < m; ++i) {
        ++count[static_cast<std::size_t>(std::min(depth[static_cast<std::size_t>(i)], max_length))];
    }
    std::uint32_t kraft = 0;
    for (int len = 1; len <= max_length; ++len) {
        kraft += count[static_cast<std::size_t>(len)] << (max_length - len);
    }
    while (kraft != (1U << max_length)) {  // over-subscribed after folding: split shorter codes
        --count[static_cast<std::size_t>(max_length)];
        for (int len = max_length - 1; len > 0; --len) {
            if (count[static_cast<std::size_t>(len)] != 0) {
                --count[static_cast<std::size_t>(len)];
                count[static_cast<std::size_t>(len + 1)] += 2;
                break;
            }
        }
        --kraft;
    }
    int i = 0;  // least frequent first: the longest codes
    for (int len = max_length; len >= 1; --len) {
        for (std::uint32_t c = 0; c < count[static_cast<std::size_t>(len)]; ++c) {
            lengths[leaves[static_cast<std::size_t>(i++)].second] = static_cast<std::uint8_t>(len);
        }
    }
}

// Canonical codes (RFC 1951 3.2.2), bit-reversed for the least-significant-first writer.
void CanonicalCodes(const std::uint8_t* lengths, int n, std::uint16_t* codes) {
    std::array<int, 16> per_length{};
    for (int s = 0; s < n; ++s) {
        ++per_length[lengths[s]];
    }
    per_length[0] = 0;
    std::array<std::uint32_t, 16> next{};
    std::uint32_t code = 0;
    for (int len = 1; len < 16; ++len) {
        code = (code + static_cast<std::uint32_t>(per_length[static_cast<std::size_t>(len - 1)]))
               << 1;
        next[static_cast<std::size_t>(len)] = code;
    }
    for (int s = 0; s < n; ++s) {
        const int len = lengths[s];
        if (len == 0) {
            codes[s] = 0;
            continue;
        }
        std::uint32_t c = next[static_cast<std::size_t>(len)]++;
        std::uint32_t reversed = 0;
        for (int b = 0; b < len; ++b) {
            reversed = (reversed << 1) | (c & 1U);
            c >>= 1;
        }
        codes[s] = static_cast<std::uint16_t>(reversed);
    }
}

void StoredBlocks(const unsigned char* data, std::size_t size, bool last, BitWriter& bits) {
    std::size_t done = 0;
    do {
        const std::size_t n = std::min(kMaxStored, size - done);
        const bool final_piece = last && done + n == size;
        bits.Put(final_piece ? 1U : 0U, 1);
        bits.Put(0U, 2);
        bits.Align();
        const std::array<unsigned char, 4> header = {
            static_cast<unsigned char>(n), static_cast<unsigned char>(n >> 8),
            static_cast<unsigned char>(~n), static_cast<unsigned char>((~n) >> 8)};
        bits.Bytes(header.data(), header.size());
        bits.Bytes(data + done, n);
        done += n;
    } while (done < size);
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

// Huffman code lengths of both alphabets, and how many of each the header lists.
void LiteralDistanceLengths(BlockCodes& codes) {
    HuffmanLengths(codes.ll_freq.data(), kLitLen, 15, codes.ll_len.data());
    HuffmanLengths(codes.d_freq.data(), kDist, 15, codes.d_len.data());
    codes.hlit = kLitLen;
    while (codes.hlit > 257 && codes.ll_len[static_cast<std::size_t>(codes.hlit - 1)] == 0) {
        --codes.hlit;
    }
    codes.hdist = kDist;
    while (codes.hdist > 1 && codes.d_len[static_cast<std::size_t>(codes.hdist - 1)] == 0) {
        --codes.hdist;
    }
}

// The code lengths of both alphabets as one run-length coded sequence (symbols 0-18), then
// the code-length code's own lengths and how many of them the header lists.
void HeaderRunLengths(BlockCodes& codes) {
    std::array<std::uint8_t, kLitLen + kDist> seq{};
    std::copy_n(codes.ll_len.begin(), codes.hlit, seq.begin());
    std::copy_n(codes.d_len.begin(), codes.hdist, seq.begin() + codes.hlit);
    const int total = codes.hlit + codes.hdist;
    const auto emit = [&codes](int symbol, int extra) {
        codes.rle[static_cast<std::size_t>(codes.n_rle++)] = {static_cast<std::uint8_t>(symbol),
                                                              static_cast<std::uint8_t>(extra)};
        ++codes.cl_freq[static_cast<std::size_t>(symbol)];
    };
    for (int i = 0; i < total;) {
        const int v = seq[static_cast<std::size_t>(i)];
        int run = 1;
        while (i + run < total && seq[static_cast<std::size_t>(i + run)] == v) {
            ++run;
        }
        i += run;
        if (v == 0) {
            for (; run >= 11; run -= std::min(run, 138)) {
                emit(18, std::min(run, 138) - 11);
            }
            if (run >= 3) {
                emit(17, run - 3);
                run = 0;
            }
        } else {
            emit(v, 0);
            --run;
            for (; run >= 3; run -= std::min(run, 6)) {
                emit(16, std::min(run, 6) - 3);
            }
        }
        for (; run > 0; --run) {
            emit(v, 0);
        }
    }
    HuffmanLengths(codes.cl_freq.data(), kCodeLen, 7, codes.cl_len.data());
    codes.hclen = kCodeLen;
    while (codes.hclen > 4 && codes.cl_len[static_cast<std::size_t>(
                                  kCodeLenOrder[static_cast<std::size_t>(codes.hclen - 1)])] == 0) {
        --codes.hclen;
    }
}

// Exact size in bits of the dynamic block (header, symbols, extra bits).
std::uint64_t DynamicBlockBits(const BlockCodes& codes) {
    std::uint64_t dynamic_bits = 3 + 5 + 5 + 4 + 3 * static_cast<std::uint64_t>(codes.hclen);
    for (int s = 0; s < kCodeLen; ++s) {
        const int extra = s == 16 ? 2 : (s == 17 ? 3 : (s == 18 ? 7 : 0));
        dynamic_bits +=
            static_cast<std::uint64_t>(codes.cl_freq[static_cast<std::size_t>(s)]) *
            static_cast<std::uint64_t>(codes.cl_len[static_cast<std::size_t>(s)] + extra);
    }
    for (int s = 0; s < kLitLen; ++s) {
        const int extra = s > kEndOfBlock ? LengthExtraBits(s) : 0;
        dynamic_bits +=
            static_cast<std::uint64_t>(codes.ll_freq[static_cast<std::size_t>(s)]) *
            static_cast<std::uint64_t>(codes.ll_len[static_cast<std::size_t>(s)] + extra);
    }
    for (int s = 0; s < kDist; ++s) {
        const int extra = DistanceExtraBits(s);
        dynamic_bits +=
            static_cast<std::uint64_t>(codes.d_freq[static_cast<std::size_t>(s)]) *
            static_cast<std::uint64_t>(codes.d_len[static_cast<std::size_t>(s)] + extra);
    }
    return dynamic_bits;
}

// The dynamic block's header: sizes, the code-length code, the run-length coded lengths.
void EmitDynamicHeader(const BlockCodes& codes,
                       const std::array<std::uint16_t, kCodeLen>& cl_code,
                       bool last,
                       BitWriter& bits) {
    bits.Put(last ? 1U : 0U, 1);
    bits.Put(2U, 2);  // dynamic Huffman codes
    bits.Put(static_cast<std::uint64_t>(codes.hlit - 257), 5);
    bits.Put(static_cast<std::uint64_t>(codes.hdist - 1), 5);
    bits.Put(static_cast<std::uint64_t>(codes.hclen - 4), 4);
    for (int k = 0; k < codes.hclen; ++k) {
        bits.Put(codes.cl_len[static_cast<std::size_t>(kCodeLenOrder[static_cast<std::size_t>(k)])],
                 3);
    }
    for (int k = 0; k < codes.n_rle; ++k) {
        const auto [symbol, extra] = codes.rle[static_cast<std::size_t>(k)];
        bits.Put(cl_code[symbol], codes.cl_len[symbol]);
        if (symbol >= 16) {
            bits.Put(extra, symbol == 16 ? 2 : (symbol == 17 ? 3 : 7));
        }
    }
}

// The whole dynamic block: header, the symbols (FindSymbols' encoding), end of block.
void EmitDynamicBlock(const BlockCodes& codes,
                      std::span<const std::uint32_t> symbols,
                      bool last,
                      BitWriter& bits) {
    const auto& ll_len = codes.ll_len;
    const auto& d_len = codes.d_len;
    std::array<std::uint16_t, kLitLen> ll_code{};
    std::array<std::uint16_t, kDist> d_code{};
    std::array<std::uint16_t, kCodeLen> cl_code{};
    CanonicalCodes(ll_len.data(), kLitLen, ll_code.data());
    CanonicalCodes(d_len.data(), kDist, d_code.data());
    CanonicalCodes(codes.cl_len.data(), kCodeLen, cl_code.data());
    EmitDynamicHeader(codes, cl_code, last, bits);
    for (const std::uint32_t s : symbols) {
        if ((s & kMatchFlag) == 0) {
            bits.Put(ll_code[s], ll_len[s]);
            continue;
        }
        const std::size_t len = (s & 0xFFU) + 3;
        const std::size_t sym = kLength.symbol[len];
        bits.Put(ll_code[sym] | (static_cast<std::uint64_t>(kLength.extra[len]) << ll_len[sym]),
                 ll_len[sym] + kLength.extra_bits[len]);
        const std::size_t d = ((s >> 8) & 0x7FFFU) + 1;
        const int dsym = DistanceSymbol(d);
        const auto ds = static_cast<std::size_t>(dsym);
        bits.Put(
            d_code[ds] | (static_cast<std::uint64_t>(d - static_cast<std::size_t>(kDistBase[ds]))
                          << d_len[ds]),
            d_len[ds] + DistanceExtraBits(dsym));
    }
    bits.Put(ll_code[kEndOfBlock], ll_len[kEndOfBlock]);
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
