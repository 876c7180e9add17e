// The datatype encoding check (io/hdf5_datatype_check.cpp) on hand-made encodings: each part
// HDF5 1.10.8 reads without a bound, cut short or broken, and the valid forms beside them.
#include "casmap/io/hdf5_datatype_check.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace casmap::io::h5 {
namespace {

using Bytes = std::vector<std::uint8_t>;

// A datatype header: class and version, 24 bits of flags, the size.
Bytes Header(unsigned version, unsigned type_class, std::uint32_t flags, std::uint32_t size) {
    return {static_cast<std::uint8_t>(version << 4U | type_class),
            static_cast<std::uint8_t>(flags & 0xFFU),
            static_cast<std::uint8_t>(flags >> 8U & 0xFFU),
            static_cast<std::uint8_t>(flags >> 16U & 0xFFU),
            static_cast<std::uint8_t>(size & 0xFFU),
            static_cast<std::uint8_t>(size >> 8U & 0xFFU),
            static_cast<std::uint8_t>(size >> 16U & 0xFFU),
            static_cast<std::uint8_t>(size >> 24U)};
}

// Fixed-point, version 1, little-endian signed, 4 bytes; offset 0, precision 32.
Bytes Int32() { return {0x10, 0x08, 0, 0, 4, 0, 0, 0, 0, 0, 32, 0}; }

Bytes operator+(Bytes a, const Bytes& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

std::optional<std::string> Check(const Bytes& b) {
    return CheckDatatypeEncoding(b.data(), b.size());
}

std::string Error(const Bytes& b) { return Check(b).value_or(""); }

// A version 2 compound of one int32 member named "a" (padded to 8), offset 0.
Bytes CompoundOfOne(const std::string& name) {
    Bytes b = Header(2, 6, 1, 4);
    b.insert(b.end(), name.begin(), name.end());
    b.resize(b.size() + (8 - name.size() % 8), 0);
    return b + Bytes{0, 0, 0, 0} + Int32();
}

TEST(DatatypeCheck, ValidEncodingsPass) {
    EXPECT_EQ(Check(Int32()), std::nullopt);
    EXPECT_EQ(Check(Header(1, 3, 0, 10)), std::nullopt);  // fixed-length string
    EXPECT_EQ(Check(CompoundOfOne("a")), std::nullopt);
    EXPECT_EQ(Check(CompoundOfOne("abcdefgh")), std::nullopt);  // 8 characters: 16 bytes
    // An enum of int32 with members "A" and "B" (names padded to 8) and their values.
    const Bytes enumerated = Header(1, 8, 2, 4) + Int32() + Bytes{'A', 0, 0, 0, 0, 0, 0, 0} +
                             Bytes{'B', 0, 0, 0, 0, 0, 0, 0} + Bytes{0, 0, 0, 0, 1, 0, 0, 0};
    EXPECT_EQ(Check(enumerated), std::nullopt);
    // A version 2 array 2 x 3 of int32: rank, 3 reserved, 2 sizes, 2 permutation indices.
    const Bytes array = Header(2, 10, 0, 24) + Bytes{2, 0, 0, 0} + Bytes{2, 0, 0, 0, 3, 0, 0, 0} +
                        Bytes{0, 0, 0, 0, 1, 0, 0, 0} + Int32();
    EXPECT_EQ(Check(array), std::nullopt);
    EXPECT_EQ(Check(Header(1, 9, 0, 16) + Int32()), std::nullopt);  // variable-length sequence
}

TEST(DatatypeCheck, EncodingsHdf5RejectsItselfAreLeftToIt) {
    EXPECT_EQ(Check(Header(4, 0, 0, 4)), std::nullopt);   // version 4
    EXPECT_EQ(Check(Header(1, 11, 0, 4)), std::nullopt);  // class 11
    EXPECT_EQ(Check(Header(1, 0, 0, 0)), std::nullopt);   // size 0
    EXPECT_EQ(Check(Header(1, 6, 0, 4)), std::nullopt);   // a compound without members
}

TEST(DatatypeCheck, PartsThatRunPastTheEndAreReported) {
    EXPECT_EQ(Error(Header(1, 1, 0, 4)),
              "datatype properties at byte 8 runs past the end (its datatype's 8 bytes)");
    EXPECT_EQ(Error(Header(1, 5, 16, 4) + Bytes(8, 'x')),
              "datatype opaque tag at byte 8 runs past the end (its datatype's 16 bytes)");
    Bytes cut = CompoundOfOne("a");
    cut.resize(cut.size() - 1);
    EXPECT_EQ(Error(cut),
              "datatype properties at byte 28 runs past the end (its datatype's 31 bytes)");
    // Two enum members declared, values for one.
    const Bytes enumerated = Header(1, 8, 2, 4) + Int32() + Bytes{'A', 0, 0, 0, 0, 0, 0, 0} +
                             Bytes{'B', 0, 0, 0, 0, 0, 0, 0} + Bytes{0, 0, 0, 0};
    EXPECT_EQ(Error(enumerated),
              "datatype enum values (2 of 4 bytes) at byte 36 run past the end (its datatype's "
              "40 bytes)");
}

TEST(DatatypeCheck, ANameWithoutItsNulIsReported) {
    Bytes b = Header(2, 6, 1, 4) + Bytes{'a', 'b', 'c'};
    EXPECT_EQ(Error(b),
              "datatype compound member 0 name at byte 8 is not NUL-terminated (its datatype's 11 "
              "bytes)");
}

TEST(DatatypeCheck, AnArrayRankAbove32IsReported) {
    // HDF5 writes the sizes into a 32-entry table without checking the rank.
    const Bytes array = Header(2, 10, 0, 4) + Bytes{40, 0, 0, 0} + Bytes(320, 1) + Int32();
    EXPECT_EQ(Error(array),
              "datatype array rank 40 at byte 8 is above 32 (its datatype's 344 bytes)");
}

TEST(DatatypeCheck, NestingDeeperThanTheLimitIsReported) {
    Bytes nested;
    for (int k = 0; k <= kMaxDatatypeDepth; ++k) {
        nested = nested + Header(1, 9, 0, 16);  // a sequence of a sequence of ...
    }
    nested = nested + Int32();
    EXPECT_EQ(Error(nested), "datatypes nested deeper than 32 (its datatype's 276 bytes)");
    nested.erase(nested.begin(), nested.begin() + 8);  // one level less
    EXPECT_EQ(Check(nested), std::nullopt);
}

}  // namespace
}  // namespace casmap::io::h5
