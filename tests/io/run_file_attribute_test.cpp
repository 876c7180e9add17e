// Run files and HDF5's attribute decoder (fuzz finding: HDF5 1.10.8 copies an attribute's name
// with strdup and reads past its buffer when no NUL ends the name inside the message). casmap
// walks a version 1 object header's attribute messages before HDF5 decodes them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
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

/// Runs /usr/bin/python3 (Debian's, with h5py) on `script`; returns its exit status.
int RunPython(const fs::path& dir, const std::string& script, std::string* out) {
    const fs::path py = dir / "writer.py";
    std::ofstream(py) << script;
    FILE* pipe = popen(("/usr/bin/python3 " + py.string() + " 2>&1").c_str(), "r");
    std::array<char, 4096> buffer{};
    while (pipe != nullptr && fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
        *out += buffer.data();
    }
    return pipe != nullptr ? pclose(pipe) : -1;
}

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

// Where the datatype of the version 1 attribute message whose name starts at `at` starts: the
// name is padded to 8 bytes.
std::size_t AttributeDatatype(const std::string& bytes, std::size_t at) {
    const auto name_bytes = static_cast<std::size_t>(static_cast<unsigned char>(bytes[at - 6]));
    return at + (name_bytes + 7) / 8 * 8;
}

TEST(RunFileAttributes, AValueLargerThanItsMessageIsAnInputError) {
    // HDF5 1.10.8 copies datatype size x elements bytes after the dataspace, whatever the
    // message's size (fuzz finding). A written file with its datatype size raised to 4096:
    std::string bytes = WrittenRun();
    const std::size_t at = AttributeName(bytes, "range_mode");
    const std::size_t type = AttributeDatatype(bytes, at);
    bytes[type + 4] = 0;
    bytes[type + 5] = 0x10;
    bytes[type + 6] = 0;
    bytes[type + 7] = 0;
    const std::string error = ReadError(bytes);
    EXPECT_NE(error.find("/scans"), std::string::npos) << error;
    EXPECT_NE(error.find("attribute message at byte " + std::to_string(at - 16)), std::string::npos)
        << error;
    EXPECT_NE(error.find("value of 1 element(s) of 4096 bytes does not fit the"), std::string::npos)
        << error;
}

TEST(RunFileAttributes, ADataspaceShorterThanItsRankIsAnInputError) {
    std::string bytes = WrittenRun();
    const std::size_t at = AttributeName(bytes, "range_mode");
    const auto type_bytes = static_cast<std::size_t>(static_cast<unsigned char>(bytes[at - 4]));
    const std::size_t space = AttributeDatatype(bytes, at) + (type_bytes + 7) / 8 * 8;
    ASSERT_EQ(static_cast<unsigned char>(bytes[space]), 1U) << "not a version 1 dataspace";
    bytes[space + 1] = 32;  // rank 32: 256 bytes of sizes
    const std::string error = ReadError(bytes);
    EXPECT_NE(error.find("its dataspace needs 264 bytes for its rank but has"), std::string::npos)
        << error;
}

TEST(RunFileAttributes, ADatatypeEncodingThatOverrunsItsPartIsAnInputError) {
    // range_mode's fixed-length string datatype (8 bytes) made a compound of one member: HDF5
    // would strdup the member's name from the bytes after the datatype.
    std::string bytes = WrittenRun();
    const std::size_t at = AttributeName(bytes, "range_mode");
    const std::size_t type = AttributeDatatype(bytes, at);
    ASSERT_EQ(static_cast<unsigned char>(bytes[type]) & 0x0FU, 3U) << "not a string datatype";
    bytes[type] = static_cast<char>(0x16);  // version 1, class 6 (compound)
    bytes[type + 1] = 1;                    // one member
    EXPECT_NE(ReadError(bytes).find(
                  "attribute message at byte " + std::to_string(at - 16) +
                  ": datatype compound member 0 name at byte 8 is not NUL-terminated (its "
                  "datatype's 8 bytes)"),
              std::string::npos)
        << ReadError(bytes);
}

TEST(RunFileAttributes, TheFuzzersValueOverreadInputIsAnInputError) {
    // The root's casmap_run_format_version (in a continuation block at byte 800): an integer
    // of 44 bytes with 8 bytes left in the message.
    const std::string bytes =
        ReadBytes(kSource / "tests/data/fuzz/run_file/regress_attribute_value_overread.h5");
    ASSERT_FALSE(bytes.empty());
    EXPECT_EQ(ReadError(bytes),
              "run.h5: / (corrupt file: attribute message at byte 824: its value of 1 "
              "element(s) of 44 bytes does not fit the 8 bytes after its dataspace)");
}

// Valid files from another writer pass the walk: h5py (HDF5 1.10.8) with every kind of
// attribute value (scalars, arrays, fixed and variable-length strings, a null dataspace,
// compound, enum, variable-length sequences, a committed datatype, a large value, enough
// attributes for continuation blocks), in the 1.6 format (version 1 headers, walked) and the
// latest (version 2, checksummed).
TEST(RunFileAttributes, FilesWrittenByH5pyPass) {
    const casmap::test::TempDir dir("run_attribute_h5py");
    std::string out;
    const int rc = RunPython(dir.Path(),
                             R"PY(
import h5py, numpy as np
def attrs(o, f):
    o.attrs["i"] = np.int64(7)
    o.attrs["b"] = True
    o.attrs["c"] = 1 + 2j
    o.attrs["grid"] = np.arange(12, dtype=np.float32).reshape(3, 4)
    o.attrs["bytes"] = np.arange(300, dtype=np.uint8)
    o.attrs["fixed"] = np.bytes_("fixed text")
    o.attrs["text"] = "variable-length text"
    o.attrs["texts"] = ["a", "bc", "def"]
    o.attrs["empty"] = h5py.Empty("f8")
    o.attrs["pair"] = np.array([(1, 2.5), (3, 4.5)], dtype=[("a", "i4"), ("b", "f8")])
    o.attrs.create("enum", [0, 1, 1], dtype=h5py.enum_dtype({"A": 0, "B": 1}, basetype="i1"))
    seqs = np.empty(2, dtype=object); seqs[0] = np.arange(3); seqs[1] = np.arange(5)
    o.attrs.create("seqs", seqs, dtype=h5py.vlen_dtype(np.int64))
    o.attrs.create("committed", np.ones(4, np.float32), dtype=f["t"])
    o.attrs["large"] = np.zeros(6000, np.float64)
    for k in range(40):
        o.attrs["n%02d" % k] = np.full(k + 1, k, np.int16)
for libver in ["earliest", "latest"]:
    with h5py.File(")PY" + dir.Path().string() +
                                 R"PY(/" + libver + ".h5", "w", libver=libver) as f:
        f["t"] = np.dtype("f4")
        f["scans/stamp_s"] = np.array([0.0, 1 / 75])
        f["scans/ranges_m"] = np.full((2, 181), 2.0, np.float32)
        f["scans/raw"] = np.full((2, 181), 2000, np.uint16)
        f["scans/status"] = np.zeros((2, 181), np.uint8)
        f["poses/stamp_s"] = np.array([0.0, 1.0])
        f["poses/xyz_m"] = np.zeros((2, 3))
        f["poses/quat_xyzw"] = np.array([[0, 0, 0, 1.0], [0, 0, 0, 1.0]])
        attrs(f, f)
        attrs(f["scans"], f)
        f["scans"].attrs["start_angle_rad"] = -np.pi / 2
        f["scans"].attrs["angle_step_rad"] = np.pi / 180
        f["scans"].attrs["beam_period_s"] = 1 / 75 / 360
)PY",
                             &out);
    ASSERT_EQ(rc, 0) << out;
    for (const char* file : {"earliest.h5", "latest.h5"}) {
        const std::string bytes = ReadBytes(dir / file);
        EXPECT_EQ(ReadError(bytes), "") << file;
    }
    // The 1.6 format's root group header is version 1, so the walk read it.
    const std::string bytes = ReadBytes(dir / "earliest.h5");
    EXPECT_EQ(bytes.find("OHDR"), std::string::npos);
}

// An attribute whose datatype is committed (attribute message version 2, datatype shared) is
// sized by the datatype message in the committed datatype's own object header, where HDF5
// reads it.
TEST(RunFileAttributes, ASharedDatatypeIsSizedWhereItIsCommitted) {
    const casmap::test::TempDir dir("run_attribute_committed");
    std::string out;
    const int rc = RunPython(dir.Path(),
                             R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "c.h5").string() +
                                 R"PY(", "w", libver="earliest") as f:
    f["t"] = np.dtype("<i2")
    f.attrs.create("c", np.arange(4, dtype=np.int16), dtype=f["t"])
    print(h5py.h5o.get_info(f["t"].id).addr)
)PY",
                             &out);
    ASSERT_EQ(rc, 0) << out;
    const std::size_t header = std::stoul(out);
    const std::string bytes = ReadBytes(dir / "c.h5");
    // The committed type's header: 16-byte prefix, its datatype message's 8-byte header, then
    // class and version 0x10 (fixed-point, version 1), 3 bytes of flags, the size (2).
    ASSERT_EQ(static_cast<unsigned char>(bytes.at(header + 24)), 0x10U);
    ASSERT_EQ(static_cast<unsigned char>(bytes.at(header + 28)), 2U);
    EXPECT_EQ(ReadError(bytes).find("corrupt file"), std::string::npos) << ReadError(bytes);

    std::string wide = bytes;
    wide[header + 28] = 64;  // the message holds 8 bytes of value and 4 of padding
    EXPECT_NE(ReadError(wide).find(
                  "its value of 4 element(s) of 64 bytes does not fit the 12 bytes after its "
                  "dataspace"),
              std::string::npos)
        << ReadError(wide);

    // The committed type's datatype message made a shared reference to its own header.
    std::string loop = bytes;
    loop[header + 20] = 0x02;  // message flags: shared
    loop[header + 24] = 2;     // shared message version 2, committed, the header's address
    loop[header + 25] = 2;
    for (int k = 0; k < 8; ++k) {
        loop[header + 26 + k] = static_cast<char>((header >> (8 * k)) & 0xFFU);
    }
    EXPECT_NE(ReadError(loop).find("its shared datatype is more than 4 references away"),
              std::string::npos)
        << ReadError(loop);
}

// The same with the committed type in a version 2 header (committed after the file was
// reopened with the latest format): the attribute in the root's version 1 header is walked, the
// reference followed into the "OHDR" header.
TEST(RunFileAttributes, ASharedDatatypeInAVersionTwoHeaderIsFollowed) {
    const casmap::test::TempDir dir("run_attribute_committed_v2");
    std::string out;
    const int rc = RunPython(dir.Path(), R"PY(
import h5py, numpy as np
name = ")PY" + (dir / "m.h5").string() + R"PY("
with h5py.File(name, "w", libver="earliest") as f:
    f["x"] = 1
with h5py.File(name, "r+", libver="latest") as f:
    f["t"] = np.dtype("<i2")
    f.attrs.create("c", np.arange(4, dtype=np.int16), dtype=f["t"])
    print(h5py.h5o.get_info(f["t"].id).addr)
)PY",
                             &out);
    ASSERT_EQ(rc, 0) << out;
    const std::size_t header = std::stoul(out);
    const std::string bytes = ReadBytes(dir / "m.h5");
    EXPECT_EQ(ReadError(bytes).find("corrupt file"), std::string::npos) << ReadError(bytes);
    // "OHDR", version 2, flags 0x20 (16 bytes of times follow), a 1-byte chunk size, then the
    // datatype message: type 1, size 2, flags 1, class and version 4, size 4.
    ASSERT_EQ(bytes.substr(header, 4), "OHDR");
    ASSERT_EQ(static_cast<unsigned char>(bytes.at(header + 5)), 0x20U);
    const std::size_t message = header + 6 + 16 + 1;
    ASSERT_EQ(static_cast<unsigned char>(bytes.at(message)), 3U);
    ASSERT_EQ(static_cast<unsigned char>(bytes.at(message + 8)), 2U);
    std::string wide = bytes;
    wide[message + 8] = 64;
    EXPECT_NE(ReadError(wide).find("its value of 4 element(s) of 64 bytes does not fit"),
              std::string::npos)
        << ReadError(wide);
}

TEST(RunFileAttributes, HeadersOfAVersionHdf5RejectsAreLeftToIt) {
    // An "OHDR" header of version 3 (HDF5 knows 2 only) is rejected by HDF5 before it decodes
    // a message; the walk accepts it without reading further. (Version 2 headers are walked: a
    // checksum guards against random corruption, not against a crafted file.)
    std::string bytes = WrittenRun();
    const std::size_t header = bytes.size() - 64;
    std::memcpy(&bytes[header], "OHDR", 4);
    bytes[header + 4] = 3;
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
