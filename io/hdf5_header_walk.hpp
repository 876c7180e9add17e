#pragma once

// The walk over an HDF5 object header's messages from the file's bytes that casmap's checks
// share (io/hdf5_object_header.cpp for attribute messages, io/hdf5_dataset_header.cpp for a
// dataset's own messages): the superblock's sizes, the header's chunks and continuation blocks,
// dataspace extents and shared (committed) messages, read the way HDF5 1.10.8 reads them.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "casmap/io/hdf5_global_heap.hpp"  // ReadAt

namespace casmap::io::h5 {

/// The most continuation blocks casmap follows in one object header (HDF5 has no limit; a
/// run file's headers have none or one).
inline constexpr int kMaxHeaderContinuations = 64;

// Object header message types (HDF5 file format specification, IV.A.2).
inline constexpr std::uint16_t kDataspaceMessage = 0x0001;
inline constexpr std::uint16_t kDatatypeMessage = 0x0003;
inline constexpr std::uint16_t kOldFillValueMessage = 0x0004;
inline constexpr std::uint16_t kFillValueMessage = 0x0005;
inline constexpr std::uint16_t kExternalFilesMessage = 0x0007;
inline constexpr std::uint16_t kLayoutMessage = 0x0008;
inline constexpr std::uint16_t kFilterPipelineMessage = 0x000B;
inline constexpr std::uint16_t kAttributeMessage = 0x000C;
inline constexpr std::uint16_t kContinuationMessage = 0x0010;
inline constexpr std::uint8_t kMessageShared = 0x02;  // message flag: a shared reference

/// A little-endian unsigned integer of `bytes` (at most 8) bytes.
[[nodiscard]] std::uint64_t DecodeLe(const std::uint8_t* p, std::size_t bytes);
/// "at byte N".
[[nodiscard]] std::string AtByte(std::uint64_t offset);

struct Superblock {
    std::size_t offsets = 0;  // size of offsets (addresses), bytes
    std::size_t lengths = 0;  // size of lengths, bytes
    // The end-of-file address the superblock stores (HDF5's end of allocation when it opens
    // the file read-only); relative to the base address, which HDF5 takes to be where it found
    // the superblock (H5F__super_read overrides a stored base that differs): byte 0 here.
    std::uint64_t end_of_file = 0;
    std::uint64_t root = 0;  // the root group's object header address
};

/// The superblock at byte 0 (versions 0-3), or nullopt when there is none or its sizes of
/// offsets and lengths are not 2, 4 or 8.
[[nodiscard]] std::optional<Superblock> ReadSuperblock(std::uint64_t file_size, const ReadAt& read);

/// What a header check reports when ReadSuperblock finds none.
inline constexpr const char* kNoSuperblockProblem =
    "no HDF5 superblock with sizes of offsets and lengths of 2, 4 or 8 at byte 0, so its object "
    "headers cannot be checked";

struct HeaderFile {
    Superblock sb;
    std::uint64_t size = 0;
    const ReadAt* read = nullptr;
};

struct HeaderMessage {
    std::uint16_t type = 0;
    std::uint8_t flags = 0;
    const std::uint8_t* data = nullptr;
    std::uint64_t size = 0;
    std::uint64_t at = 0;  // where its message header starts in the file
};
using VisitMessage = std::function<std::optional<std::string>(const HeaderMessage&)>;

/// Walks the header at `start` the way HDF5 lays it out (the first chunk and each continuation
/// block) and calls `visit` on each message (its data valid during the call); returns the first
/// reason `visit` or the walk gives (a block outside the file, a message overrunning its
/// block, more than kMaxHeaderContinuations blocks). A version 2 header is walked only if `v2`
/// (every caller now asks for it: its checksum is no defence against a crafted file).
[[nodiscard]] std::optional<std::string> WalkHeader(const HeaderFile& file,
                                                    std::uint64_t start,
                                                    bool v2,
                                                    const VisitMessage& visit);

/// Walks the blocks of the object header at `address` (nullopt: the root group's, from the
/// superblock) the way H5O_protect loads them, the first chunk and every continuation block, in
/// either header version, and returns the reason the first bad one gives: a block outside the
/// file or above 16 MiB, more than kMaxHeaderContinuations blocks, a message overrunning its
/// block. HDF5 1.10.8 crashes in H5F__accum_read when a continuation block lies past the end of
/// the file (fuzz finding), before any message is decoded, so this runs before HDF5 loads a
/// header at all. nullopt also when there is no superblock at byte 0 (H5Fopen decides).
[[nodiscard]] std::optional<std::string> FindCorruptHeaderBlocks(
    std::optional<std::uint64_t> address, std::uint64_t file_size, const ReadAt& read);

/// A dataspace message as H5O__sdspace_decode reads it: version 1 or 2, rank (at most 32),
/// flags (bit 0: maximum sizes follow), then version 2 a type byte (2: null, no elements),
/// version 1 five reserved bytes; then `rank` sizes and, with the flag, `rank` maxima of
/// `lengths` bytes each.
struct Extent {
    std::uint64_t need = 0;      // bytes the decoder reads
    std::uint64_t elements = 0;  // the product of the sizes; UINT64_MAX: more than 2^64 - 1
    std::uint8_t rank = 0;
    std::vector<std::uint64_t> sizes;   // filled when `need` fits the message
    std::vector<std::uint64_t> maxima;  // likewise, when the message has maxima
};
/// nullopt when HDF5 rejects the version or rank before it reads sizes.
[[nodiscard]] std::optional<Extent> DecodeExtent(const std::uint8_t* p,
                                                 std::uint64_t size,
                                                 std::size_t lengths);

/// A datatype or dataspace message, or the one a shared reference points at.
struct Resolved {
    std::optional<std::string> error;  // "<what>: <reason>"
    bool found = false;  // false: HDF5 cannot read it either, or casmap does not follow it
    std::vector<std::uint8_t> bytes;
    std::uint64_t at = 0;  // where the message's header starts in the file
};

/// The message `m` (a datatype, dataspace or other sharable message) or, if it is shared, the first
/// message of its type in the object header its reference points at (H5O__shared_read), at most
/// 4 references away; one in the shared message heap is not followed. `what` starts errors.
[[nodiscard]] Resolved ResolveMessage(const HeaderFile& file,
                                      const HeaderMessage& m,
                                      const std::string& what);

}  // namespace casmap::io::h5
