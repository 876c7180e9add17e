#include "casmap/io/deflate_block.hpp"

#include <algorithm>

namespace casmap::io::h5 {
namespace {

// The order in which a dynamic block header lists the code-length code's lengths.
constexpr std::array<int, kCodeLen> kCodeLenOrder = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                     11, 4,  12, 3, 13, 2, 14, 1, 15};

int DistanceExtraBits(int symbol) { return symbol < 4 ? 0 : symbol / 2 - 1; }

int LengthExtraBits(int symbol) {  // for symbols 257..285
    return symbol < 265 || symbol == 285 ? 0 : (symbol - 261) / 4;
}

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

}  // namespace

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

}  // namespace casmap::io::h5
