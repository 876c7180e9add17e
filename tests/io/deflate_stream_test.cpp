// The run-file writer's zlib encoder (io/deflate_stream.hpp): every stream must inflate with
// zlib (what HDF5's deflate filter uses) to exactly the input, whatever the data and layout.
#include <gtest/gtest.h>
#include <zlib.h>

#if defined(CASMAP_HAVE_LIBDEFLATE)
#include <libdeflate.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "casmap/io/deflate_stream.hpp"

namespace casmap::io::h5 {
namespace {

using Bytes = std::vector<unsigned char>;

Bytes Inflate(const Bytes& stream, std::size_t size) {
    Bytes out(size + 1);  // one spare byte: a stream that decodes to more would show
    uLongf got = out.size();
    const int rc = uncompress(out.data(), &got, stream.data(), stream.size());
    EXPECT_EQ(rc, Z_OK) << "zlib uncompress failed";
    out.resize(rc == Z_OK ? got : 0);
    return out;
}

// Encodes, checks the stream inflates (zlib, and libdeflate's stricter decoder when built
// with it) to the input and is deterministic; returns its size.
std::size_t RoundTrip(const Bytes& in, const DeflateLayout& layout) {
    Bytes stream;
    DeflateZlib(in, layout, stream);
    EXPECT_EQ(Inflate(stream, in.size()), in);
#if defined(CASMAP_HAVE_LIBDEFLATE)
    libdeflate_decompressor* d = libdeflate_alloc_decompressor();
    Bytes out(in.size());
    std::size_t got = 0;
    EXPECT_EQ(
        libdeflate_zlib_decompress(d, stream.data(), stream.size(), out.data(), out.size(), &got),
        LIBDEFLATE_SUCCESS);
    EXPECT_EQ(got, in.size());
    EXPECT_EQ(out, in);
    libdeflate_free_decompressor(d);
#endif
    Bytes again;
    DeflateZlib(in, layout, again);
    EXPECT_EQ(again, stream);
    return stream.size();
}

Bytes RandomBytes(std::size_t n, std::mt19937_64& gen) {
    Bytes b(n);
    for (auto& x : b) {
        x = static_cast<unsigned char>(gen());
    }
    return b;
}

TEST(DeflateStream, Adler32MatchesZlib) {
    const std::string text = "Wikipedia";
    const Bytes b(text.begin(), text.end());
    EXPECT_EQ(Adler32(b), 0x11E60398U);
    std::mt19937_64 gen(7);
    const Bytes big = RandomBytes(100000, gen);
    EXPECT_EQ(Adler32(big),
              static_cast<std::uint32_t>(adler32(1, big.data(), static_cast<uInt>(big.size()))));
    EXPECT_EQ(Adler32({}), 1U);
}

TEST(DeflateStream, EdgeSizesRoundTrip) {
    std::mt19937_64 gen(11);
    for (const std::size_t n : {0UL, 1UL, 3UL, 4UL, 5UL, 8UL, 9UL, 258UL, 259UL, 65535UL, 65536UL,
                                65537UL, 131071UL, 200003UL}) {
        SCOPED_TRACE("size " + std::to_string(n));
        RoundTrip(Bytes(n, 0), {});
        RoundTrip(RandomBytes(n, gen), {});
        RoundTrip(RandomBytes(n, gen), {.segment_bytes = 1000, .distance_a = 4, .distance_b = 724});
    }
}

TEST(DeflateStream, RandomDataIsStoredAtAlmostItsSize) {
    std::mt19937_64 gen(13);
    const Bytes in = RandomBytes(262144, gen);
    const std::size_t size = RoundTrip(in, {});
    EXPECT_LE(size, in.size() + 2 + 4 + 5 * 5 + 4);  // zlib wrapper + stored block headers
}

TEST(DeflateStream, RunsAndRowRepeatsCompress) {
    EXPECT_LT(RoundTrip(Bytes(262144, 0), {}), 2000U);  // 258-byte matches at distance 1
    std::mt19937_64 gen(17);
    const Bytes row = RandomBytes(181, gen);
    Bytes rows;
    for (int r = 0; r < 1400; ++r) {
        rows.insert(rows.end(), row.begin(), row.end());
        rows[rows.size() - 1 - static_cast<std::size_t>(r % 181)] ^= 0x5A;  // one change a row
    }
    const std::size_t size =
        RoundTrip(rows, {.segment_bytes = 0, .distance_a = 1, .distance_b = 181});
    EXPECT_LT(size, rows.size() / 10);
    // A distance beyond the window is not used (the data then stays nearly random).
    RoundTrip(rows, {.segment_bytes = 0, .distance_a = 40000, .distance_b = 0, .hashed = false});
}

TEST(DeflateStream, SkewedFrequenciesGetLengthLimitedCodes) {
    // Symbol k appears fib(k) times: an unlimited Huffman code would be 25 bits deep.
    std::vector<std::uint64_t> fib = {1, 1};
    while (fib.size() < 26) {
        fib.push_back(fib[fib.size() - 1] + fib[fib.size() - 2]);
    }
    Bytes in;
    for (std::size_t k = 0; k < fib.size(); ++k) {
        in.insert(in.end(), fib[k], static_cast<unsigned char>(k * 9));
    }
    std::mt19937_64 gen(19);
    std::shuffle(in.begin(), in.end(), gen);
    // No matches (distances unused): all literals with the skewed code; one segment.
    const std::size_t size = RoundTrip(
        in, {.segment_bytes = in.size(), .distance_a = 0, .distance_b = 0, .hashed = false});
    EXPECT_LT(size, in.size() / 3);
}

TEST(DeflateStream, ShuffledFloatPlanesWithNaNRoundTrip) {
    // Like /scans/ranges_m: 181 beams, about a third NaN, mm-quantised ranges that repeat from
    // scan to scan; byte-shuffled into planes as the writer does, and not shuffled.
    std::mt19937_64 gen(23);
    std::normal_distribution<double> noise(0.0, 0.01);
    const std::size_t beams = 181;
    const std::size_t rows = 362;
    std::vector<float> v(rows * beams);
    for (std::size_t r = 0; r < rows; ++r) {
        for (std::size_t b = 0; b < beams; ++b) {
            const double truth = 1.0 + 0.02 * static_cast<double>(b);
            v[r * beams + b] =
                b % 3 == 0 ? std::numeric_limits<float>::quiet_NaN()
                           : static_cast<float>(std::round((truth + noise(gen)) * 1000.0) * 0.001);
        }
    }
    Bytes plain(v.size() * 4);
    std::memcpy(plain.data(), v.data(), plain.size());
    Bytes shuffled(plain.size());
    for (std::size_t b = 0; b < 4; ++b) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            shuffled[b * v.size() + i] = plain[i * 4 + b];
        }
    }
    EXPECT_LT(
        RoundTrip(shuffled, {.segment_bytes = v.size(), .distance_a = 1, .distance_b = beams}),
        plain.size() * 3 / 4);
    EXPECT_LT(RoundTrip(plain, {.segment_bytes = 0, .distance_a = 4, .distance_b = 4 * beams}),
              plain.size() * 3 / 4);
}

TEST(DeflateStream, RandomStructuredInputsRoundTrip) {
    // Mixtures of runs, copies at the two distances, near copies and noise, random layouts.
    const std::uint64_t seed = 20261128;
    std::mt19937_64 gen(seed);
    for (int trial = 0; trial < 300; ++trial) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
        const std::size_t n = gen() % 70000;
        const std::size_t da = 1 + gen() % 8;
        const std::size_t db = gen() % 3 == 0 ? 0 : 1 + gen() % 2000;
        Bytes in(n);
        for (std::size_t i = 0; i < n;) {
            const std::size_t len = std::min<std::size_t>(n - i, 1 + gen() % 600);
            const int kind = static_cast<int>(gen() % 5);
            for (std::size_t k = 0; k < len; ++k, ++i) {
                if (kind == 0) {
                    in[i] = static_cast<unsigned char>(gen());
                } else if (kind == 1) {
                    in[i] = i >= da ? in[i - da] : 0;
                } else if (kind == 2) {
                    in[i] = db != 0 && i >= db ? in[i - db] : 7;
                } else if (kind == 3) {
                    in[i] = (i >= db && db != 0 ? in[i - db] : 0) ^
                            static_cast<unsigned char>(gen() % 16 == 0);
                } else {
                    in[i] = static_cast<unsigned char>(gen() % 3);
                }
            }
        }
        const std::size_t segment = gen() % 2 == 0 ? 0 : 1 + gen() % 40000;
        RoundTrip(in, {.segment_bytes = segment,
                       .distance_a = da,
                       .distance_b = db,
                       .hashed = gen() % 4 != 0});
    }
}

TEST(DeflateStream, SegmentsLongerThanAStoredBlockRoundTrip) {
    // The writer's byte planes: a 256 KiB chunk of 4-byte elements is four 65536-byte segments,
    // one byte more than a stored block holds, so an incompressible plane is stored as two
    // blocks (only the last of the last segment final); 2-byte and larger planes likewise.
    std::mt19937_64 gen(29);
    for (const std::size_t segment : {65536UL, 131072UL, 200000UL}) {
        SCOPED_TRACE("segment " + std::to_string(segment));
        Bytes mixed = RandomBytes(4 * segment, gen);
        std::fill(mixed.begin() + static_cast<std::ptrdiff_t>(segment),
                  mixed.begin() + static_cast<std::ptrdiff_t>(2 * segment), 0);  // compressible
        RoundTrip(mixed, {.segment_bytes = segment, .distance_a = 1, .distance_b = 181});
        RoundTrip(RandomBytes(segment + 1, gen), {.segment_bytes = segment});
    }
}

}  // namespace
}  // namespace casmap::io::h5
