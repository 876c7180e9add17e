// Run files and HDF5's global heap (fuzz finding: HDF5 1.10.8 loops forever in H5HG_read on a
// corrupt collection behind a variable-length string). Format version 2 writes no
// variable-length data; version 1 files are read after a check of their collections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/hdf5_global_heap.hpp"
#include "casmap/io/run_file.hpp"
#include "run_file_fixtures.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
using test::ReadBytes;
using test::SmallRun;
namespace fs = std::filesystem;

const fs::path kSource = CASMAP_SOURCE_DIR;

std::optional<std::string> Check(const std::string& bytes) {
    return h5::FindCorruptGlobalHeap(bytes.size(), [&](std::uint64_t at, std::size_t n, void* out) {
        if (at >= bytes.size()) {
            return std::size_t{0};
        }
        const std::size_t got = std::min<std::size_t>(n, bytes.size() - at);
        std::memcpy(out, bytes.data() + at, got);
        return got;
    });
}

// A little-endian 8-byte length.
void PutLength(std::string& bytes, std::size_t at, std::uint64_t value) {
    for (int i = 0; i < 8; ++i) {
        bytes[at + static_cast<std::size_t>(i)] = static_cast<char>((value >> (8 * i)) & 0xFFU);
    }
}

TEST(RunFileHeap, NewFilesHoldNoGlobalHeapAndRoundTrip) {
    const casmap::test::TempDir tmp("run_heap_new");
    const fs::path& dir = tmp.Path();
    const RunData run = SmallRun();
    WriteRunFile(dir / "run.h5", run);
    const std::string bytes = ReadBytes(dir / "run.h5");
    EXPECT_EQ(bytes.find("GCOL"), std::string::npos) << "a version 2 file has a global heap";
    const RunData back = ReadRunFile(dir / "run.h5");
    EXPECT_EQ(back.config_yaml, run.config_yaml);
    ASSERT_TRUE(back.format.has_value());
    EXPECT_EQ(back.format->mode, run.format->mode);
    EXPECT_EQ(back.format->units, run.format->units);

    RunData empty = run;
    empty.config_yaml.clear();
    WriteRunFile(dir / "empty.h5", empty);
    EXPECT_EQ(ReadRunFile(dir / "empty.h5").config_yaml, "");
}

TEST(RunFileHeap, VersionOneFileWithVariableLengthStringsIsStillRead) {
    // Written by h5py like casmap's version 1 (tests/data/fuzz/make_seeds.py): config_yaml,
    // range_mode and range_units are variable-length strings in one global heap collection.
    const fs::path seed = kSource / "tests/data/fuzz/run_file/seed_2x5.h5";
    const std::string bytes = ReadBytes(seed);
    ASSERT_NE(bytes.find("GCOL"), std::string::npos);
    EXPECT_EQ(Check(bytes), std::nullopt);
    const RunData run = ReadRunFile(seed);
    EXPECT_EQ(run.config_yaml, "seed: 1\n");
    ASSERT_TRUE(run.format.has_value());
    EXPECT_EQ(run.format->mode, core::RangeMode::k8m);
    EXPECT_EQ(ReadRunFileImage(bytes, "seed.h5").config_yaml, "seed: 1\n");
}

TEST(RunFileHeap, TheFuzzersEndlessLoopInputIsAnInputError) {
    // libFuzzer's input that made H5HG_read loop forever: a free-space object of 0 bytes.
    const fs::path hang = kSource / "tests/data/bad_inputs/run_corrupt_global_heap.h5";
    try {
        (void)ReadRunFile(hang);
        FAIL() << "accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("run_corrupt_global_heap.h5: / attribute config_yaml"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("global heap collection at byte 2048: free space of 0 bytes"),
                  std::string::npos)
            << what;
    }
    EXPECT_THROW((void)ReadRunFileImage(ReadBytes(hang), "hang.h5"), InputError);
}

TEST(RunFileHeap, EveryWayTheWalkCanStallOrOverrunIsFound) {
    const std::string good = ReadBytes(kSource / "tests/data/fuzz/run_file/seed_2x5.h5");
    const std::size_t at = good.find("GCOL");
    ASSERT_NE(at, std::string::npos);
    const std::size_t first = at + 16;  // the first object header

    std::string zero_free = good;  // index 0, size 0: HDF5's walk stands still
    zero_free[first] = 0;
    zero_free[first + 1] = 0;
    PutLength(zero_free, first + 8, 0);
    EXPECT_NE(Check(zero_free).value_or("").find("free space of 0 bytes"), std::string::npos);

    std::string backwards = good;  // index 0, size wraps the walk backwards
    backwards[first] = 0;
    backwards[first + 1] = 0;
    PutLength(backwards, first + 8, ~std::uint64_t{15});
    EXPECT_TRUE(Check(backwards).has_value());

    std::string wraps = good;  // index 1, padded size wraps to 0
    PutLength(wraps, first + 8, ~std::uint64_t{15});
    EXPECT_NE(Check(wraps).value_or("").find("overruns"), std::string::npos);

    std::string outside = good;  // the collection declares more bytes than the file has
    PutLength(outside, at + 8, good.size());
    EXPECT_NE(Check(outside).value_or("").find("inside the file"), std::string::npos);

    std::string tiny = good;  // below HDF5's 4096-byte minimum
    PutLength(tiny, at + 8, 64);
    EXPECT_TRUE(Check(tiny).has_value());

    std::string other_version = zero_free;  // HDF5 rejects version 2 before decoding
    other_version[at + 4] = 2;
    EXPECT_EQ(Check(other_version), std::nullopt);

    std::string no_superblock = good;
    no_superblock[1] = 'X';
    EXPECT_NE(Check(no_superblock).value_or("").find("superblock"), std::string::npos);
}

}  // namespace
}  // namespace casmap::io
