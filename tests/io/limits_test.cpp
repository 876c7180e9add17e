// Hostile small inputs: sizes declared in a file are checked against core/limits.hpp before
// anything is allocated, bad values in run files are rejected naming file and field, YAML
// duplicate keys and alias bombs are rejected (docs/limits.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/yaml_util.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("limits_" + name); }

template <typename F>
std::string ErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

// ---------------------------------------------------------------------------------------------
// Run files

RunData SmallRun(int scans) {
    RunData run;
    for (int i = 0; i < scans; ++i) {
        core::Scan s;
        s.stamp_s = 0.1 * i;
        s.start_angle_rad = 0.0;
        s.angle_step_rad = 0.0174533;
        s.beam_period_s = 3.7e-5;
        s.beams.assign(5, core::Beam{1.5F, core::BeamStatus::kOk});
        run.scans.push_back(s);
    }
    return run;
}

// A run file whose /scans/stamp_s declares `n` scans (chunked, never written: the file stays
// a few kilobytes) beside a valid rest.
void WriteHugeDeclaredRun(const fs::path& path, hsize_t n) {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t group = H5Gcreate2(file, "scans", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    const hsize_t chunk = 1024;
    H5Pset_chunk(dcpl, 1, &chunk);
    H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER);
    const hid_t d =
        H5Dcreate2(group, "stamp_s", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Gclose(group);
    H5Fclose(file);
}

TEST(Limits, RunFileDeclaringAHugeScanCountIsRejectedBeforeAllocating) {
    const fs::path path = FreshDir("huge_run") / "huge.h5";
    WriteHugeDeclaredRun(path, 1000000000);
    ASSERT_LT(fs::file_size(path), 100000U);
    const std::string message = ErrorOf([&] { (void)ReadRunFile(path); });
    EXPECT_THAT(message, HasSubstr("huge.h5"));
    EXPECT_THAT(message, HasSubstr("/scans/stamp_s"));
    EXPECT_THAT(message, HasSubstr("1000000000"));
    EXPECT_THAT(message, HasSubstr("limit 100000"));
}

// Writes `run`, then reads it back expecting an InputError.
std::string RunFileError(const std::string& name, const RunData& run) {
    const fs::path path = FreshDir(name) / "run.h5";
    WriteRunFile(path, run);
    return ErrorOf([&] { (void)ReadRunFile(path); });
}

TEST(Limits, RunFileWithANegativeRangeOnAnOkBeamIsRejected) {
    RunData run = SmallRun(3);
    run.scans[1].beams[2].range_m = -1.0F;
    const std::string message = RunFileError("negative_range", run);
    EXPECT_THAT(message, HasSubstr("run.h5: /scans/ranges_m[1, 2] = -1"));
}

TEST(Limits, RunFileWithZeroAngleStepIsRejected) {
    RunData run = SmallRun(3);
    for (core::Scan& s : run.scans) {
        s.angle_step_rad = 0.0;
    }
    EXPECT_THAT(RunFileError("zero_step", run), HasSubstr("/scans attribute angle_step_rad = 0"));
}

TEST(Limits, RunFileWithNegativeBeamPeriodIsRejected) {
    RunData run = SmallRun(3);
    for (core::Scan& s : run.scans) {
        s.beam_period_s = -1.0;
    }
    EXPECT_THAT(RunFileError("beam_period", run), HasSubstr("/scans attribute beam_period_s = -1"));
}

TEST(Limits, RunFileWithReversedOrEqualStampsIsRejected) {
    RunData reversed = SmallRun(3);
    reversed.scans[2].stamp_s = 0.05;
    EXPECT_THAT(RunFileError("reversed", reversed), HasSubstr("/scans/stamp_s[2] = 0.05"));
    RunData equal = SmallRun(3);
    equal.scans[1].stamp_s = equal.scans[0].stamp_s;
    EXPECT_THAT(RunFileError("equal", equal), HasSubstr("must increase strictly"));
}

TEST(Limits, RunFileImageReadsLikeTheFile) {
    const fs::path path = FreshDir("image") / "run.h5";
    WriteRunFile(path, SmallRun(4));
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const RunData back = ReadRunFileImage(bytes, "memory.h5");
    EXPECT_EQ(back.scans.size(), 4U);
    EXPECT_THAT(ErrorOf([&] { (void)ReadRunFileImage(bytes.substr(0, 100), "cut.h5"); }),
                HasSubstr("cut.h5: run file"));
}

// ---------------------------------------------------------------------------------------------
// TIFF maps

// A little-endian TIFF header whose first directory declares `w` x `h` float pixels and no
// pixel data at all.
std::string TiffHeader(std::uint32_t w, std::uint32_t h) {
    std::string b = std::string("II*\0", 4) + std::string("\x08\0\0\0", 4);
    const auto u16 = [&](std::uint32_t v) {
        b += static_cast<char>(v & 0xff);
        b += static_cast<char>((v >> 8) & 0xff);
    };
    const auto u32 = [&](std::uint32_t v) {
        u16(v & 0xffff);
        u16(v >> 16);
    };
    const std::uint32_t tags[][3] = {{256, 4, w}, {257, 4, h},   {258, 3, 32}, {259, 3, 1},
                                     {262, 3, 1}, {273, 4, 200}, {277, 3, 1},  {278, 4, 1},
                                     {279, 4, 4}, {339, 3, 3}};
    u16(10);
    for (const auto& t : tags) {
        u16(t[0]);
        u16(t[1]);
        u32(1);
        u32(t[2]);
    }
    u32(0);
    b.resize(210, '\0');
    return b;
}

TEST(Limits, TiffHeaderDeclaringTenGigapixelsIsRejectedNamingTheFile) {
    const fs::path path = FreshDir("tiff") / "huge.tiff";
    std::ofstream(path, std::ios::binary) << TiffHeader(100000, 100000);
    const std::string message = ErrorOf([&] { (void)ReadMapTiff(path); });
    EXPECT_THAT(message, HasSubstr("huge.tiff: TIFF header: width x length = 100000 x 100000"));
    EXPECT_THAT(message, HasSubstr("pixel limit 25000000"));
}

// tiff_map_fuzz (session 8): a second width tag of 4 after a first of 65283. libtiff sized the
// image by the first (a 3.2 GB allocation) while the header check kept the second.
TEST(Limits, TiffWithASizeTagGivenTwiceIsRejected) {
    std::string bytes = TiffHeader(65283, 12090);
    // Entry 7 (RowsPerStrip) becomes a second ImageWidth of 4: tag 256, type LONG, value 4.
    const std::size_t entry = 8 + 2 + 12 * 7;
    bytes[entry] = '\x00';
    bytes[entry + 1] = '\x01';
    bytes[entry + 8] = '\x04';
    const std::string message = ErrorOf([&] { (void)DecodeMapTiff(bytes, "twice.tiff"); });
    EXPECT_THAT(
        message,
        HasSubstr("twice.tiff: TIFF header: tag = 256 (given twice in the first directory)"));
}

TEST(Limits, TiffWithADirectoryBeyondTheFileIsRejected) {
    std::string bytes = TiffHeader(2, 2);
    bytes[4] = '\x7f';  // first directory at 0x007f007f, far beyond the 210 bytes
    bytes[6] = '\x7f';
    const std::string message = ErrorOf([&] { (void)DecodeMapTiff(bytes, "far.tiff"); });
    EXPECT_THAT(message, HasSubstr("far.tiff: TIFF header: offset"));
}

// ---------------------------------------------------------------------------------------------
// YAML

TEST(Limits, YamlDuplicateKeysAreRejected) {
    const std::string message =
        ErrorOf([] { (void)LoadYamlText("a: 1\nb: 2\na: 3\n", "dup.yaml"); });
    EXPECT_THAT(message, HasSubstr("dup.yaml:3:1: a (duplicate key)"));
}

// Complex keys (found by rig_yaml_fuzz: `?` then a sequence made the rig reader's key.as<string>()
// throw a yaml-cpp conversion error past every InputError handler) are rejected on load, for
// every YAML file casmap reads.
TEST(Limits, YamlKeysMustBePlainNames) {
    for (const auto& [text, where, kind] :
         {std::tuple{"? [a, b]\n: 1\n", "keys.yaml:1:3", "<sequence>"},
          std::tuple{"top:\n  ? {a: 1}\n  : 2\n", "keys.yaml:2:5", "<map>"},
          std::tuple{"?\n: 3\n", "keys.yaml", "<empty>"}}) {
        const std::string message = ErrorOf([&] { (void)LoadYamlText(text, "keys.yaml"); });
        EXPECT_THAT(message, HasSubstr(std::string("yaml key = ") + kind +
                                       " (map keys must be plain names)"))
            << text;
        EXPECT_THAT(message, HasSubstr(where)) << text;
    }
    EXPECT_NO_THROW((void)LoadYamlText("a: 1\n'quoted key': 2\n3: 4\n", "keys.yaml"));
}

TEST(Limits, YamlAliasBombStopsQuicklyWithAShortMessage) {
    std::string text = "a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]\n";
    for (int i = 1; i < 12; ++i) {  // 9^12 nodes once expanded
        const std::string prev = "*a" + std::to_string(i - 1);
        text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev;
        for (int k = 1; k < 9; ++k) {
            text += ", " + prev;
        }
        text += "]\n";
    }
    const auto start = std::chrono::steady_clock::now();
    const std::string message = ErrorOf([&] { (void)LoadYamlText(text, "bomb.yaml"); });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_THAT(message, HasSubstr("bomb.yaml"));
    EXPECT_THAT(message, HasSubstr("yaml nodes"));
    EXPECT_LT(message.size(), 200U);
    EXPECT_LT(seconds, 10.0);
}

TEST(Limits, YamlNestingDepthIsBounded) {
    const std::string text = std::string(100, '[') + std::string(100, ']');
    EXPECT_THAT(ErrorOf([&] { (void)LoadYamlText(text, "deep.yaml"); }), HasSubstr("deep.yaml"));
}

TEST(Limits, YamlFileSizeIsBounded) {
    const fs::path path = FreshDir("yaml_size") / "big.yaml";
    {
        std::ofstream out(path);
        const std::string line = "# " + std::string(1000, 'x') + "\n";
        for (int i = 0; i < 5000; ++i) {
            out << line;
        }
    }
    EXPECT_THAT(ErrorOf([&] { (void)LoadYamlFile(path.string()); }),
                HasSubstr("big.yaml: file size (bytes) = 5015000 (YAML file limit 4194304"));
}

TEST(Limits, GridOfABillionCellsIsRejected) {
    core::GridGeometry grid;
    grid.rows = 100000;
    grid.cols = 10000;
    EXPECT_THAT(ErrorOf([&] { grid.Validate(); }),
                HasSubstr("cells (rows x cols) = 1000000000 (grid cell limit 25000000"));
}

TEST(Limits, LongBadValuesAreQuotedShortOnOneLine) {
    const std::string value = std::string(100000, 'v') + "\nsecond line";
    const std::string message = MakeInputError("f.yaml", "field", value, "rule").what();
    EXPECT_LT(message.size(), 200U);
    EXPECT_EQ(message.find('\n'), std::string::npos);
    EXPECT_THAT(message, HasSubstr("(100012 characters)"));
}

}  // namespace
}  // namespace casmap::io
