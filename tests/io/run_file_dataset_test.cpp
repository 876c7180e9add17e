// Run files and HDF5's dataset header decoders: before H5Dopen2, casmap checks the messages a
// version 1 dataset header holds (datatype, dataspace, layout, filter pipeline, fill value,
// external file list) the way HDF5 1.10.8 decodes them. Each test patches one field of a file
// casmap wrote (HDF5 1.6 format: version 1 headers), found by walking the header here, and
// expects the exact InputError.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/hdf5_dataset_header.hpp"
#include "casmap/io/hdf5_util.hpp"
#include "casmap/io/run_file.hpp"
#include "run_file_fixtures.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
using test::MakeRun;
using test::ReadBytes;
namespace fs = std::filesystem;

std::uint64_t Le(const std::string& bytes, std::size_t at, std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) {
        v |= std::uint64_t{static_cast<unsigned char>(bytes.at(at + i))} << (8 * i);
    }
    return v;
}

void PutLe(std::string& bytes, std::size_t at, std::size_t n, std::uint64_t v) {
    for (std::size_t i = 0; i < n; ++i) {
        bytes.at(at + i) = static_cast<char>((v >> (8 * i)) & 0xFFU);
    }
}

// The object header address of `object` in the file at `path` (HDF5 reports it).
std::uint64_t HeaderAddress(const fs::path& path, const std::string& object) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    H5O_info_t info{};
    const herr_t got =
        H5Oget_info_by_name2(file, object.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT);
    H5Fclose(file);
    EXPECT_GE(got, 0) << object;
    return info.addr;
}

struct Message {
    std::uint16_t type = 0;
    std::size_t at = 0;    // its 8-byte message header
    std::size_t size = 0;  // its data, from at + 8
};

// The messages of the version 1 header at `header` (16-byte prefix, 8-byte message headers,
// continuation messages of two 8-byte fields), in order.
std::vector<Message> Messages(const std::string& bytes, std::size_t header) {
    EXPECT_EQ(bytes.at(header), 1) << "not a version 1 object header";
    std::vector<std::pair<std::size_t, std::size_t>> blocks = {
        {header + 16, static_cast<std::size_t>(Le(bytes, header + 8, 4))}};
    std::vector<Message> out;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        for (std::size_t pos = blocks[b].first; pos + 8 <= blocks[b].first + blocks[b].second;) {
            const Message m{static_cast<std::uint16_t>(Le(bytes, pos, 2)), pos,
                            static_cast<std::size_t>(Le(bytes, pos + 2, 2))};
            if (m.type == 0x10) {
                blocks.emplace_back(Le(bytes, pos + 8, 8), Le(bytes, pos + 16, 8));
            }
            out.push_back(m);
            pos += 8 + m.size;
        }
    }
    return out;
}

Message Find(const std::string& bytes, std::size_t header, std::uint16_t type) {
    for (const Message& m : Messages(bytes, header)) {
        if (m.type == type) {
            return m;
        }
    }
    ADD_FAILURE() << "no message of type " << type;
    return {};
}

std::string ReadError(const std::string& bytes) {
    try {
        (void)ReadRunFileImage(bytes, "run.h5");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A run casmap wrote whose /scans/ranges_m (8 x 181 floats) is chunked and deflated.
struct Written {
    std::string bytes;
    std::size_t ranges = 0;  // /scans/ranges_m's object header
};

Written WrittenRun() {
    const casmap::test::TempDir dir("run_dataset");
    WriteRunFile(dir / "run.h5", MakeRun(8, 181));
    return {ReadBytes(dir / "run.h5"),
            static_cast<std::size_t>(HeaderAddress(dir / "run.h5", "/scans/ranges_m"))};
}

std::string Expected(const std::string& rule) {
    return "run.h5: /scans/ranges_m (corrupt file: " + rule + ")";
}

constexpr std::uint16_t kDataspace = 1;
constexpr std::uint16_t kDatatype = 3;
constexpr std::uint16_t kFillValue = 5;
constexpr std::uint16_t kLayout = 8;
constexpr std::uint16_t kPipeline = 11;

TEST(RunFileDatasets, WrittenFilesPass) {
    const Written w = WrittenRun();
    EXPECT_EQ(ReadError(w.bytes), "");
    // Version 3 layout, chunked (class 2), 3 dimensions (rank 2 + the element).
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    ASSERT_EQ(w.bytes.at(layout.at + 8), 3);
    ASSERT_EQ(w.bytes.at(layout.at + 9), 2);
    ASSERT_EQ(w.bytes.at(layout.at + 10), 3);
}

TEST(RunFileDatasets, ADatatypeEncodingOutsideItsMessageIsAnInputError) {
    Written w = WrittenRun();
    const Message type = Find(w.bytes, w.ranges, kDatatype);
    // The float datatype made an array (version 2, class 10) of rank 40: HDF5 would write 40
    // sizes into its 32-entry table.
    w.bytes[type.at + 8] = 0x2A;
    w.bytes[type.at + 16] = 40;
    EXPECT_EQ(ReadError(w.bytes), Expected("datatype message at byte " + std::to_string(type.at) +
                                           ": datatype array rank 40 at byte 8 is above 32 (its "
                                           "datatype's " +
                                           std::to_string(type.size) + " bytes)"));
}

TEST(RunFileDatasets, ADataspaceShorterThanItsRankIsAnInputError) {
    Written w = WrittenRun();
    const Message space = Find(w.bytes, w.ranges, kDataspace);
    ASSERT_EQ(w.bytes.at(space.at + 8), 1) << "not a version 1 dataspace";
    w.bytes[space.at + 9] = 32;
    const bool maxima = (w.bytes.at(space.at + 10) & 1) != 0;
    EXPECT_EQ(ReadError(w.bytes),
              Expected("dataspace message at byte " + std::to_string(space.at) +
                       ": its dataspace needs " + std::to_string(8 + 32 * 8 * (maxima ? 2 : 1)) +
                       " bytes for its rank but has " + std::to_string(space.size)));
}

TEST(RunFileDatasets, AMaximumBelowItsSizeIsAnInputError) {
    Written w = WrittenRun();
    const Message space = Find(w.bytes, w.ranges, kDataspace);
    ASSERT_EQ(w.bytes.at(space.at + 9), 2);
    // Give it maxima (flag bit 0) after the two sizes: 8 x 181 with a maximum of 4 rows. The
    // message (8 + 2 x 8 bytes) has room only if HDF5 wrote maxima, so write them in place.
    ASSERT_GE(space.size, 8U + 4 * 8) << "no room for maxima";
    w.bytes[space.at + 10] = 1;
    PutLe(w.bytes, space.at + 8 + 8 + 16, 8, 4);
    PutLe(w.bytes, space.at + 8 + 8 + 24, 8, 181);
    EXPECT_EQ(ReadError(w.bytes), Expected("dataspace message at byte " + std::to_string(space.at) +
                                           ": its maximum size 4 of dimension 0 is below its "
                                           "size 8"));
}

TEST(RunFileDatasets, ACompactLayoutLargerThanItsMessageIsAnInputError) {
    // HDF5 1.10.8 copies a compact layout's data (size: 2 bytes in version 3) with memcpy from
    // the message whatever the message's size.
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    w.bytes[layout.at + 9] = 0;  // compact
    PutLe(w.bytes, layout.at + 10, 2, 4096);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("layout message at byte " + std::to_string(layout.at) +
                       ": its compact data of 4096 bytes does not fit the " +
                       std::to_string(layout.size - 4) + " bytes after its size"));
}

TEST(RunFileDatasets, AChunkOfTheWrongRankIsAnInputError) {
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    w.bytes[layout.at + 10] = 2;  // the dataspace has rank 2: the chunk needs 3 dimensions
    EXPECT_EQ(ReadError(w.bytes),
              Expected("layout message at byte " + std::to_string(layout.at) +
                       ": its chunk has 2 dimensions but a dataspace of rank 2 needs 3"));
}

TEST(RunFileDatasets, AChunkDimensionOfZeroIsAnInputError) {
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    // Version 3 chunked: version, class, dimensionality, the B-tree's address, 4 bytes each.
    PutLe(w.bytes, layout.at + 8 + 3 + 8 + 4, 4, 0);
    EXPECT_EQ(ReadError(w.bytes), Expected("layout message at byte " + std::to_string(layout.at) +
                                           ": its chunk dimension 1 is 0"));
}

TEST(RunFileDatasets, ALayoutFieldPastItsMessageIsAnInputError) {
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    // 33 dimensions (HDF5's most) of 4 bytes from byte 11 of a 24-byte message.
    w.bytes[layout.at + 10] = 33;
    EXPECT_EQ(
        ReadError(w.bytes),
        Expected("layout message at byte " + std::to_string(layout.at) +
                 ": chunk dimensions at byte " + std::to_string(11 + 4 * ((layout.size - 11) / 4)) +
                 " overrun its " + std::to_string(layout.size) + " bytes"));
}

TEST(RunFileDatasets, ContiguousDataPastTheEndOfTheFileIsAnInputError) {
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    // Made contiguous (class 1: address, size) 16 bytes before the superblock's end-of-file
    // address (superblock version 0: the third address after byte 24), 64 bytes long.
    ASSERT_EQ(w.bytes.at(8), 0) << "not a version 0 superblock";
    const std::uint64_t eof = Le(w.bytes, 24 + 16, 8);
    ASSERT_EQ(eof, w.bytes.size());
    w.bytes[layout.at + 9] = 1;
    PutLe(w.bytes, layout.at + 10, 8, eof - 16);
    PutLe(w.bytes, layout.at + 18, 8, 64);
    EXPECT_EQ(
        ReadError(w.bytes),
        Expected("layout message at byte " + std::to_string(layout.at) +
                 ": its contiguous data at byte " + std::to_string(eof - 16) +
                 " of 64 bytes ends past the file's end-of-file address " + std::to_string(eof)));
}

// casmap's deflate (and shuffle) filters in a version 1 pipeline: version, count, 6 reserved;
// per filter id, name length, flags, number of values, the name padded to 8, the values.
TEST(RunFileDatasets, AFilterNameWithoutItsNulIsAnInputError) {
    Written w = WrittenRun();
    const Message pipeline = Find(w.bytes, w.ranges, kPipeline);
    ASSERT_EQ(w.bytes.at(pipeline.at + 8), 1) << "not a version 1 pipeline";
    const std::size_t name = Le(w.bytes, pipeline.at + 8 + 8 + 2, 2);
    ASSERT_GT(name, 0U);
    const std::size_t first = pipeline.at + 8 + 8 + 8;
    for (std::size_t k = 0; k < name; ++k) {
        w.bytes[first + k] = 'x';
    }
    EXPECT_EQ(ReadError(w.bytes),
              Expected("filter pipeline message at byte " + std::to_string(pipeline.at) +
                       ": filter 0's name is not NUL-terminated within its " +
                       std::to_string(name) + " bytes"));
}

TEST(RunFileDatasets, FilterValuesPastTheirMessageAreAnInputError) {
    Written w = WrittenRun();
    const Message pipeline = Find(w.bytes, w.ranges, kPipeline);
    const std::size_t name = Le(w.bytes, pipeline.at + 8 + 8 + 2, 2);
    PutLe(w.bytes, pipeline.at + 8 + 8 + 6, 2, 4095);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("filter pipeline message at byte " + std::to_string(pipeline.at) +
                       ": filter 0's 4095 client data values at byte " + std::to_string(16 + name) +
                       " overrun its " + std::to_string(pipeline.size) + " bytes"));
}

TEST(RunFileDatasets, AFillValueLargerThanItsMessageIsAnInputError) {
    Written w = WrittenRun();
    const Message fill = Find(w.bytes, w.ranges, kFillValue);
    // Version 2: allocation time, fill time, defined, then the size and the value.
    ASSERT_EQ(w.bytes.at(fill.at + 8), 2) << "not a version 2 fill value message";
    w.bytes[fill.at + 8 + 3] = 1;
    PutLe(w.bytes, fill.at + 8 + 4, 4, 4096);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("fill value message at byte " + std::to_string(fill.at) +
                       ": its fill value of 4096 bytes does not fit the " +
                       std::to_string(fill.size - 8) + " bytes after its size"));
}

TEST(RunFileDatasets, MoreExternalFilesThanItsSlotsIsAnInputError) {
    // The fill value message (8 bytes) made an external file list: version 1, 3 reserved
    // bytes, 1 slot allocated, 5 used. HDF5 would write 5 slots into an array of 1.
    Written w = WrittenRun();
    const Message fill = Find(w.bytes, w.ranges, kFillValue);
    ASSERT_GE(fill.size, 8U);
    PutLe(w.bytes, fill.at, 2, 7);
    w.bytes[fill.at + 8] = 1;
    PutLe(w.bytes, fill.at + 12, 2, 1);
    PutLe(w.bytes, fill.at + 14, 2, 5);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("external file list message at byte " + std::to_string(fill.at) +
                       ": it uses 5 slots of its 1 allocated"));
}

TEST(RunFileDatasets, AChunkElementOtherThanTheDatatypeIsAnInputError) {
    // HDF5 sizes its chunk buffers from the chunk's dimensions but copies elements of the
    // datatype's size (fuzz finding: a 14-byte float read past 4-byte chunk elements).
    Written w = WrittenRun();
    const Message type = Find(w.bytes, w.ranges, kDatatype);
    ASSERT_EQ(Le(w.bytes, type.at + 8 + 4, 4), 4U);
    PutLe(w.bytes, type.at + 8 + 4, 4, 8);
    EXPECT_EQ(
        ReadError(w.bytes),
        Expected("layout message at byte " + std::to_string(Find(w.bytes, w.ranges, kLayout).at) +
                 ": its chunk's element dimension of 4 bytes is not the datatype's size of "
                 "8 bytes"));
}

TEST(RunFileDatasets, AChunkPastAFixedMaximumIsAnInputError) {
    // 8 x 181 with no unlimited dimension: a chunk of 2 x 200 columns (HDF5 refuses to create
    // one; 1.10.8 opens it and copies past the chunk it inflated: fuzz finding).
    Written w = WrittenRun();
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    PutLe(w.bytes, layout.at + 8 + 3 + 8 + 4, 4, 200);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("layout message at byte " + std::to_string(layout.at) +
                       ": its chunk dimension 1 of 200 exceeds the dataspace's fixed maximum 181"));
}

TEST(RunFileDatasets, TheFuzzersChunkInputsAreInputErrors) {
    const fs::path dir = fs::path(CASMAP_SOURCE_DIR) / "tests/data/fuzz/run_file";
    // seed_v3_chunked.h5 with /scans/ranges_m's float datatype size 4 -> 14 bytes, and with its
    // chunk's second dimension 181 -> 46 336 (1 112 064 bytes a chunk).
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_chunk_element_size.h5")),
              Expected("layout message at byte 5144: its chunk's element dimension of 4 bytes is "
                       "not the datatype's size of 14 bytes"));
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_chunk_past_fixed_maximum.h5")),
              Expected("layout message at byte 5144: its chunk dimension 1 of 46336 exceeds the "
                       "dataspace's fixed maximum 181"));
}

// HDF5 1.10.8 crashes (a read through a null pointer in H5F__accum_read) loading an object
// header whose continuation block lies past the end of the file, before it decodes anything:
// casmap walks the root group's blocks before H5Fopen and every other object's before HDF5
// loads it (fuzz finding on the root group).
TEST(RunFileDatasets, AHeaderBlockOutsideTheFileIsAnInputError) {
    const casmap::test::TempDir dir("run_dataset_blocks");
    WriteRunFile(dir / "run.h5", MakeRun(8, 181));
    const std::string bytes = ReadBytes(dir / "run.h5");
    for (const std::string object : {"/", "/scans", "/scans/ranges_m"}) {
        std::string patched = bytes;
        const std::size_t header = HeaderAddress(dir / "run.h5", object);
        // A continuation message (an 8-byte address and an 8-byte length) pointing 64 bytes
        // past the end, made of the header's own continuation or of a null message.
        std::optional<Message> slot;
        for (const Message& m : Messages(bytes, header)) {
            if ((m.type == 0x10 || m.type == 0) && m.size >= 16 && !slot) {
                slot = m;
            }
        }
        ASSERT_TRUE(slot.has_value()) << object;
        PutLe(patched, slot->at, 2, 0x10);
        PutLe(patched, slot->at + 8, 8, bytes.size() + 64);
        PutLe(patched, slot->at + 16, 8, 128);
        EXPECT_EQ(ReadError(patched),
                  "run.h5: " + object + " (corrupt file: object header block at byte " +
                      std::to_string(bytes.size() + 64) + " of 128 bytes lies outside the file's " +
                      std::to_string(bytes.size()) + " bytes)");
    }
}

TEST(RunFileDatasets, ContiguousDataOfAnotherSizeIsAnInputError) {
    // /scans/stamp_s (8 doubles, contiguous, version 3 layout: address and size).
    const casmap::test::TempDir dir("run_dataset_contiguous");
    WriteRunFile(dir / "run.h5", MakeRun(8, 181));
    std::string bytes = ReadBytes(dir / "run.h5");
    const std::size_t header = HeaderAddress(dir / "run.h5", "/scans/stamp_s");
    const Message layout = Find(bytes, header, kLayout);
    ASSERT_EQ(bytes.at(layout.at + 9), 1) << "not contiguous";
    ASSERT_EQ(Le(bytes, layout.at + 18, 8), 64U);
    PutLe(bytes, layout.at + 18, 8, 32);
    EXPECT_EQ(ReadError(bytes),
              "run.h5: /scans/stamp_s (corrupt file: layout message at byte " +
                  std::to_string(layout.at) +
                  ": its contiguous data of 32 bytes is not the 8 element(s) of 8 bytes its "
                  "dataspace and datatype say)");
}

TEST(RunFileDatasets, TheFuzzersHeaderInputsAreInputErrors) {
    const fs::path dir = fs::path(CASMAP_SOURCE_DIR) / "tests/data/fuzz/run_file";
    // seed_v3_chunked.h5 with the root group's continuation moved to byte 2^64 - 1 (HDF5's
    // undefined address), and with
    // /scans/stamp_s's double sized 2 113 929 224 bytes (HDF5 allocated 2 GB to convert it).
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_root_continuation_outside.h5")),
              "run.h5: / (corrupt file: object header block at byte 18446744073709551615 of 255 "
              "bytes lies outside the file's 23488 bytes)");
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_contiguous_type_size.h5")),
              "run.h5: /scans/stamp_s (corrupt file: layout message at byte 1816: its contiguous "
              "data of 48 bytes is not the 6 element(s) of 2113929224 bytes its dataspace and "
              "datatype say)");
}

// HDF5 1.10.8 copies a whole chunk out of whatever its filters returned: a chunk whose deflate
// stream inflates to fewer bytes than its dimensions hold is read past its buffer. Here the
// dataspace's maxima are made unlimited and the chunk twice as tall as the data it stores.
TEST(RunFileDatasets, AChunkThatInflatesShortIsAnInputError) {
    Written w = WrittenRun();
    const Message space = Find(w.bytes, w.ranges, kDataspace);
    ASSERT_EQ(w.bytes.at(space.at + 10) & 1, 1) << "no maxima";
    PutLe(w.bytes, space.at + 8 + 8 + 16, 8, ~std::uint64_t{0});
    const Message layout = Find(w.bytes, w.ranges, kLayout);
    ASSERT_EQ(Le(w.bytes, layout.at + 8 + 3 + 8, 4), 8U) << "not one chunk of 8 rows";
    PutLe(w.bytes, layout.at + 8 + 3 + 8, 4, 16);
    EXPECT_EQ(ReadError(w.bytes),
              Expected("its chunk at (0, 0) holds 5792 bytes after its filters, not the 11584 "
                       "of its dimensions"));
}

TEST(RunFileDatasets, AFilterCasmapDoesNotReadIsAnInputError) {
    const casmap::test::TempDir dir("run_dataset_filter");
    int status = 0;
    const std::string out = test::RunPython(dir.Path(), R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "s.h5").string() + R"PY(", "w", libver="earliest") as f:
    f["scans/stamp_s"] = np.array([0.0, 1 / 75])
    f["scans/ranges_m"] = np.full((2, 181), 2.0, np.float32)
    f.create_dataset("scans/raw", data=np.full((2, 181), 2000, np.uint16), chunks=(2, 181),
                     scaleoffset=0)
    f["scans/status"] = np.zeros((2, 181), np.uint8)
    f["scans"].attrs["start_angle_rad"] = 0.0
    f["scans"].attrs["angle_step_rad"] = np.pi / 180
    f["scans"].attrs["beam_period_s"] = 1e-5
    f["poses/stamp_s"] = np.zeros(0)
    f["poses/xyz_m"] = np.zeros((0, 3))
    f["poses/quat_xyzw"] = np.zeros((0, 4))
)PY",
                                            &status);
    ASSERT_EQ(status, 0) << out;
    EXPECT_EQ(ReadError(ReadBytes(dir / "s.h5")),
              "run.h5: /scans/raw (unsupported encoding: its filter 6 is not one casmap reads "
              "(deflate, shuffle, Fletcher-32))");
}

TEST(RunFileDatasets, TheFuzzersChunkAndBlockInputsAreInputErrors) {
    const fs::path dir = fs::path(CASMAP_SOURCE_DIR) / "tests/data/fuzz/run_file";
    // regress_chunk_past_fixed_maximum.h5 with /scans/ranges_m's maxima made unlimited: the
    // chunk of 6 x 46 336 floats stores 4 344 bytes.
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_chunk_inflates_short.h5")),
              Expected("its chunk at (0, 0) holds 4344 bytes after its filters, not the 1112064 "
                       "of its dimensions"));
    // /config_yaml's layout turned into version 2 compact data of 0 bytes for its 31-byte
    // string: HDF5 copied the string from a null buffer.
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_compact_data_size.h5")),
              "run.h5: /config_yaml (corrupt file: layout message at byte 1024: its compact data "
              "of 0 bytes is not the 1 element(s) of 31 bytes its dataspace and datatype say)");
    // An object header block of 0 bytes (the check passed a null buffer to memcpy: UBSan).
    EXPECT_EQ(ReadError(ReadBytes(dir / "regress_empty_header_block.h5")),
              "run.h5: / (corrupt file: its object header cannot be read)");
}

std::optional<std::string> CheckDataset(const std::string& bytes, std::uint64_t header) {
    return h5::FindCorruptDatasetMessages(
        header, bytes.size(), [&](std::uint64_t at, std::size_t n, void* out) {
            const std::size_t got =
                at >= bytes.size() ? 0 : std::min<std::size_t>(n, bytes.size() - at);
            std::memcpy(out, bytes.data() + at, got);
            return got;
        });
}

// Valid files from another writer pass: h5py (HDF5 1.10.8) in the 1.6 format (version 1
// headers, every dataset walked: contiguous, compact, chunked with deflate, shuffle and
// Fletcher-32, unlimited maxima, fill values, 2-D, fixed and variable-length strings, a
// committed datatype, a null dataspace, a scalar) and the latest (version 2 headers, left to
// their checksums); a run file of each reads.
TEST(RunFileDatasets, FilesWrittenByH5pyPass) {
    const casmap::test::TempDir dir("run_dataset_h5py");
    int status = 0;
    const std::string out = test::RunPython(dir.Path(), R"PY(
import h5py, numpy as np
for libver in ["earliest", "latest"]:
    with h5py.File(")PY" + dir.Path().string() + R"PY(/" + libver + ".h5", "w", libver=libver) as f:
        f.attrs["casmap_run_format_version"] = np.int32(2)
        f["config_yaml"] = "seed: 1\n"
        f["scans/stamp_s"] = np.array([0.0, 1 / 75])
        f.create_dataset("scans/ranges_m", data=np.full((2, 181), 2.0, np.float32),
                         chunks=(1, 181), compression="gzip", shuffle=True, fletcher32=True)
        f.create_dataset("scans/raw", data=np.full((2, 181), 2000, np.uint16), chunks=(2, 64),
                         maxshape=(None, 181), compression="gzip", fillvalue=7)
        f.create_dataset("scans/status", data=np.zeros((2, 181), np.uint8))
        f["scans"].attrs["start_angle_rad"] = -np.pi / 2
        f["scans"].attrs["angle_step_rad"] = np.pi / 180
        f["scans"].attrs["beam_period_s"] = 1 / 75 / 360
        f["poses/stamp_s"] = np.array([0.0, 1.0])
        f["poses/xyz_m"] = np.zeros((2, 3))
        f["poses/quat_xyzw"] = np.array([[0, 0, 0, 1.0], [0, 0, 0, 1.0]])
        dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        dcpl.set_layout(h5py.h5d.COMPACT)
        space = h5py.h5s.create_simple((4, 5))
        h5py.h5d.create(f.id, b"compact", h5py.h5t.NATIVE_DOUBLE, space, dcpl=dcpl).write(
            h5py.h5s.ALL, h5py.h5s.ALL, np.arange(20.0).reshape(4, 5))
        f["fixed"] = np.array([b"abc", b"defgh"])
        f.create_dataset("texts", data=["a", "bc"], dtype=h5py.string_dtype())
        f["t"] = np.dtype("<i2")
        f.create_dataset("committed", data=np.arange(6, dtype=np.int16), dtype=f["t"])
        f.create_dataset("empty", data=h5py.Empty("f4"))
        f["scalar"] = 3.5
        f.create_dataset("unwritten", shape=(100, 100), dtype="f8")
        for name in ["config_yaml", "scans/stamp_s", "scans/ranges_m", "scans/raw",
                     "scans/status", "compact", "fixed", "texts", "committed", "empty",
                     "scalar", "unwritten"]:
            print(libver, name, h5py.h5o.get_info(f[name].id).addr)
)PY",
                                            &status);
    ASSERT_EQ(status, 0) << out;
    std::istringstream lines(out);
    std::string libver;
    std::string name;
    std::uint64_t header = 0;
    int checked = 0;
    while (lines >> libver >> name >> header) {
        const std::string bytes = ReadBytes(dir / (libver + ".h5"));
        EXPECT_EQ(CheckDataset(bytes, header), std::nullopt) << libver << " " << name;
        EXPECT_EQ(bytes.at(header), libver == "earliest" ? 1 : 'O') << libver << " " << name;
        ++checked;
    }
    EXPECT_EQ(checked, 24) << out;
    for (const char* file : {"earliest.h5", "latest.h5"}) {
        EXPECT_EQ(ReadError(ReadBytes(dir / file)), "") << file;
    }
}

// A dataset whose datatype is committed: HDF5 reads the datatype message in the committed
// type's own header (H5O__shared_read), and so does the check.
TEST(RunFileDatasets, ASharedDatatypeIsCheckedWhereItIsCommitted) {
    const casmap::test::TempDir dir("run_dataset_committed");
    int status = 0;
    const std::string out = test::RunPython(dir.Path(), R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "c.h5").string() + R"PY(", "w", libver="earliest") as f:
    f["t"] = np.dtype("<i2")
    f.create_dataset("d", data=np.arange(6, dtype=np.int16), dtype=f["t"])
    print(h5py.h5o.get_info(f["d"].id).addr, h5py.h5o.get_info(f["t"].id).addr)
)PY",
                                            &status);
    ASSERT_EQ(status, 0) << out;
    std::istringstream fields(out);
    std::size_t dataset = 0;
    std::size_t committed = 0;
    fields >> dataset >> committed;
    std::string bytes = ReadBytes(dir / "c.h5");
    const Message reference = Find(bytes, dataset, kDatatype);
    ASSERT_EQ(bytes.at(reference.at + 4) & 0x02, 0x02) << "not a shared datatype";
    EXPECT_EQ(CheckDataset(bytes, dataset), std::nullopt);
    // The committed type made an array (version 2, class 10) of rank 33.
    const Message type = Find(bytes, committed, kDatatype);
    bytes[type.at + 8] = 0x2A;
    bytes[type.at + 16] = 33;
    EXPECT_EQ(CheckDataset(bytes, dataset),
              "datatype message at byte " + std::to_string(type.at) +
                  ": datatype array rank 33 at byte 8 is above 32 (its datatype's " +
                  std::to_string(type.size) + " bytes)");
}

// A version 2 header's checksum (Jenkins lookup3, which HDF5 exports) only guards against
// random corruption: a crafted file recomputes it. The dataset check walks version 2 headers
// too: h5py's latest format, a compact dataset whose layout says 4 096 bytes, checksum fixed.
extern "C" std::uint32_t H5_checksum_metadata(const void* data,
                                              std::size_t len,
                                              std::uint32_t initval);

TEST(RunFileDatasets, AVersionTwoHeaderWithItsChecksumFixedIsChecked) {
    const casmap::test::TempDir dir("run_dataset_v2");
    int status = 0;
    const std::string out = test::RunPython(dir.Path(), R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "v2.h5").string() + R"PY(", "w", libver="latest") as f:
    dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
    dcpl.set_layout(h5py.h5d.COMPACT)
    space = h5py.h5s.create_simple((4, 5))
    h5py.h5d.create(f.id, b"compact", h5py.h5t.NATIVE_DOUBLE, space, dcpl=dcpl).write(
        h5py.h5s.ALL, h5py.h5s.ALL, np.arange(20.0).reshape(4, 5))
    print(h5py.h5o.get_info(f["compact"].id).addr)
)PY",
                                            &status);
    ASSERT_EQ(status, 0) << out;
    const std::size_t header = std::stoul(out);
    std::string bytes = ReadBytes(dir / "v2.h5");
    EXPECT_EQ(CheckDataset(bytes, header), std::nullopt);
    // "OHDR", version 2, flags; times (flag 0x20), phase change values (0x10); the first
    // chunk's size in 1 << (flags & 3) bytes; messages of type 1, size 2, flags 1 (creation
    // order 2 more with flag 0x04); the chunk's checksum after it.
    ASSERT_EQ(bytes.substr(header, 4), "OHDR");
    const auto flags = static_cast<unsigned char>(bytes.at(header + 5));
    std::size_t pos = header + 6 + ((flags & 0x20U) != 0 ? 16 : 0) + ((flags & 0x10U) != 0 ? 4 : 0);
    const std::size_t size_bytes = std::size_t{1} << (flags & 0x03U);
    const std::size_t chunk = Le(bytes, pos, size_bytes);
    pos += size_bytes;
    const std::size_t end = pos + chunk;
    const std::size_t message_header = (flags & 0x04U) != 0 ? 6 : 4;
    std::size_t layout = 0;
    for (std::size_t at = pos; at + message_header <= end;
         at += message_header + Le(bytes, at + 1, 2)) {
        if (bytes.at(at) == kLayout) {
            layout = at;
        }
    }
    ASSERT_NE(layout, 0U);
    const std::size_t data = layout + message_header;
    ASSERT_EQ(bytes.at(data + 1), 0) << "not compact";  // version, class, 2-byte size
    PutLe(bytes, data + 2, 2, 4096);
    PutLe(bytes, end, 4, H5_checksum_metadata(bytes.data() + header, end - header, 0));
    const std::size_t message_size = Le(bytes, layout + 1, 2);
    EXPECT_EQ(CheckDataset(bytes, header),
              "layout message at byte " + std::to_string(layout) +
                  ": its compact data of 4096 bytes does not fit the " +
                  std::to_string(message_size - 4) + " bytes after its size");
}

}  // namespace
}  // namespace casmap::io
