// Run files and HDF5's attribute decoder (fuzz finding: HDF5 1.10.8 copies an attribute's name
// with strdup and reads past its buffer when no NUL ends the name inside the message). casmap
// walks a version 1 object header's attribute messages before HDF5 decodes them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/hdf5_object_header.hpp"
#include "casmap/io/run_file.hpp"
#include "run_file_fixtures.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
using test::ReadBytes;
using test::SmallRun;
namespace fs = std::filesystem;

const fs::path kSource = CASMAP_SOURCE_DIR;

std::string WrittenRun() {
    const casmap::test::TempDir dir("run_attribute");
    WriteRunFile(dir / "run.h5", SmallRun());
    return ReadBytes(dir / "run.h5");
}

// Where the attribute message whose name is `name` starts: its 8-byte message header lies
// before the message's own header (version 1: 8 bytes) and the name.
std::size_t AttributeName(const std::string& bytes, const std::string& name) {
    const std::size_t at = bytes.find(name + std::string(1, '\0'));
    EXPECT_NE(at, std::string::npos) << "no attribute named " << name;
    EXPECT_EQ(static_cast<unsigned char>(bytes[at - 8]), 1U) << "not a version 1 message";
    return at;
}

std::string ReadError(const std::string& bytes) {
    try {
        (void)ReadRunFileImage(bytes, "run.h5");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(RunFileAttributes, WrittenFilesPassAndRoundTrip) {
    const std::string bytes = WrittenRun();
    EXPECT_EQ(ReadError(bytes), "");
}

TEST(RunFileAttributes, ANameWithoutItsNulIsAnInputError) {
    std::string bytes = WrittenRun();
    const std::size_t at = AttributeName(bytes, "range_mode");
    const auto name_bytes = static_cast<std::size_t>(static_cast<unsigned char>(bytes[at - 6]));
    ASSERT_EQ(name_bytes, std::string("range_mode").size() + 1);
    bytes[at + name_bytes - 1] = 'X';  // the NUL the name size counts
    const std::string error = ReadError(bytes);
    EXPECT_NE(error.find("/scans"), std::string::npos) << error;
    EXPECT_NE(error.find("not NUL-terminated within its 11 bytes"), std::string::npos) << error;
}

TEST(RunFileAttributes, SizesThatOverrunTheMessageAreAnInputError) {
    std::string bytes = WrittenRun();
    const std::size_t at = AttributeName(bytes, "range_mode");
    bytes[at - 4] = static_cast<char>(0xFF);  // datatype size 0xFF.. bytes
    bytes[at - 3] = static_cast<char>(0x7F);
    const std::string error = ReadError(bytes);
    EXPECT_NE(error.find("do not fit its"), std::string::npos) << error;
}

TEST(RunFileAttributes, TheFuzzersOverreadInputsAreInputErrors) {
    // The second also stores a base address of 50 in its superblock, which HDF5 ignores (it
    // takes the superblock's own place, byte 0): the walk must read the same bytes HDF5 does.
    for (const char* file :
         {"regress_attribute_name_overread.h5", "regress_attribute_name_moved_base.h5"}) {
        const std::string bytes = ReadBytes(kSource / "tests/data/fuzz/run_file" / file);
        ASSERT_FALSE(bytes.empty()) << file;
        EXPECT_NE(ReadError(bytes).find("(corrupt file: attribute message at byte"),
                  std::string::npos)
            << file << ": " << ReadError(bytes);
    }
}

TEST(RunFileAttributes, VersionTwoHeadersAreLeftToTheirChecksum) {
    // A header that starts with "OHDR" is checked by HDF5 (Jenkins lookup3 checksum) before it
    // decodes a message; the walk accepts it without reading further.
    std::string bytes = WrittenRun();
    const std::size_t header = bytes.size() - 64;
    std::memcpy(&bytes[header], "OHDR", 4);
    const auto read = [&](std::uint64_t at, std::size_t n, void* out) {
        const std::size_t got =
            at >= bytes.size() ? 0 : std::min<std::size_t>(n, bytes.size() - at);
        std::memcpy(out, bytes.data() + at, got);
        return got;
    };
    EXPECT_EQ(h5::FindCorruptAttributeMessages(header, bytes.size(), read), std::nullopt);
    // ... while an address outside the file is reported.
    const std::optional<std::string> outside =
        h5::FindCorruptAttributeMessages(bytes.size() + 100, bytes.size(), read);
    ASSERT_TRUE(outside.has_value());
    EXPECT_NE(outside->find("outside the file"), std::string::npos) << *outside;
}

}  // namespace
}  // namespace casmap::io
