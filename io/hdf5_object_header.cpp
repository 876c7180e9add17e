#include "casmap/io/hdf5_object_header.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <set>
#include <vector>

namespace casmap::io::h5 {
namespace {

constexpr std::array<std::uint8_t, 8> kSuperblockSignature = {0x89, 'H',  'D',  'F',
                                                              '\r', '\n', 0x1a, '\n'};
constexpr std::uint16_t kAttributeMessage = 0x000C;
constexpr std::uint16_t kContinuationMessage = 0x0010;
constexpr std::uint8_t kMessageShared = 0x02;       // the message holds a shared reference
constexpr std::size_t kV1PrefixBytes = 16;          // 12 bytes and 4 of alignment
constexpr std::size_t kV1MessageHeaderBytes = 8;    // type 2, size 2, flags 1, reserved 3
constexpr std::uint64_t kMaxBlockBytes = 1U << 24;  // a header chunk HDF5 would load (16 MiB)

std::uint64_t Decode(const std::uint8_t* p, std::size_t bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
        value |= static_cast<std::uint64_t>(p[i]) << (8U * i);
    }
    return value;
}

std::uint64_t Align8(std::uint64_t n) { return (n + 7) / 8 * 8; }

std::string At(std::uint64_t offset) { return "at byte " + std::to_string(offset); }

struct Superblock {
    std::size_t offsets = 0;  // size of offsets (addresses), bytes
    std::size_t lengths = 0;  // size of lengths, bytes
    // Object addresses are relative to the base address, which HDF5 takes to be where it found
    // the superblock (H5F__super_read overrides a stored base that differs): byte 0 here.
};

// Superblock versions 0-1 keep the sizes at bytes 13-14, versions 2-3 at bytes 9-10.
std::optional<Superblock> ReadSuperblock(std::uint64_t file_size, const ReadAt& read) {
    std::array<std::uint8_t, 32> head{};
    if (file_size < head.size() || read(0, head.size(), head.data()) != head.size() ||
        !std::equal(kSuperblockSignature.begin(), kSuperblockSignature.end(), head.begin())) {
        return std::nullopt;
    }
    const std::uint8_t version = head[8];
    if (version > 3) {
        return std::nullopt;
    }
    Superblock s;
    s.offsets = version <= 1 ? head[13] : head[9];
    s.lengths = version <= 1 ? head[14] : head[10];
    if ((s.offsets != 2 && s.offsets != 4 && s.offsets != 8) ||
        (s.lengths != 2 && s.lengths != 4 && s.lengths != 8)) {
        return std::nullopt;
    }
    return s;
}

// A dataspace as H5O__sdspace_decode reads it: version 1 or 2, rank (at most 32), flags (bit 0:
// maximum sizes follow), then version 2 a type byte (2: null, no elements), version 1 five
// reserved bytes; then `rank` sizes and, with the flag, `rank` maxima of `lengths` bytes each.
// The number of elements is the product of the sizes.
struct Extent {
    std::uint64_t need = 0;      // bytes the decoder reads
    std::uint64_t elements = 0;  // UINT64_MAX: more than 2^64 - 1
};

std::optional<Extent> DecodeExtent(const std::uint8_t* p, std::uint64_t size, std::size_t lengths) {
    constexpr std::uint8_t kMaxRank = 32;       // H5S_MAX_RANK
    constexpr std::uint8_t kNullDataspace = 2;  // version 2 type byte
    constexpr std::uint8_t kMaximaPresent = 1;  // flags
    if (size < 4 || p[0] < 1 || p[0] > 2 || p[1] > kMaxRank) {
        return std::nullopt;  // HDF5 rejects the version or rank before it reads sizes
    }
    const std::uint8_t rank = p[1];
    Extent e;
    e.need =
        (p[0] == 1 ? 8 : 4) + std::uint64_t{rank} * lengths * ((p[2] & kMaximaPresent) ? 2 : 1);
    if (e.need > size) {
        return e;
    }
    const std::uint8_t* dims = p + (p[0] == 1 ? 8 : 4);
    e.elements = p[0] == 2 && p[3] == kNullDataspace ? 0 : 1;
    for (std::uint8_t k = 0; k < rank && e.elements != 0; ++k) {
        const std::uint64_t n = Decode(dims + std::size_t{k} * lengths, lengths);
        e.elements = n != 0 && e.elements > UINT64_MAX / n ? UINT64_MAX : e.elements * n;
    }
    return e;
}

// The attribute's value, which H5O_attr_decode copies with memcpy (datatype size times the
// dataspace's elements) from the bytes after the dataspace without comparing that size with the
// message's (fuzz finding, docs/fuzzing.md). A datatype or dataspace that is shared (attribute
// message flags, versions 2-3) is stored elsewhere and not checked here.
struct Parts {
    const std::uint8_t* datatype = nullptr;
    std::uint64_t datatype_bytes = 0;
    const std::uint8_t* dataspace = nullptr;
    std::uint64_t dataspace_bytes = 0;
    std::uint64_t left = 0;  // the message's bytes after the dataspace (and its padding)
};

std::optional<std::string> CheckValue(const Parts& parts,
                                      const Superblock& sb,
                                      const std::string& what) {
    constexpr std::uint64_t kDatatypeHeaderBytes = 8;  // class and version 4, size 4
    constexpr std::uint8_t kVariableLength = 9;        // datatype class
    const std::optional<Extent> extent =
        DecodeExtent(parts.dataspace, parts.dataspace_bytes, sb.lengths);
    if (!extent) {
        return std::nullopt;
    }
    if (extent->need > parts.dataspace_bytes) {
        return what + ": its dataspace needs " + std::to_string(extent->need) +
               " bytes for its rank but has " + std::to_string(parts.dataspace_bytes);
    }
    if (parts.datatype_bytes < kDatatypeHeaderBytes) {
        return what + ": its datatype of " + std::to_string(parts.datatype_bytes) +
               " bytes is shorter than a datatype's 8-byte header";
    }
    std::uint64_t element = Decode(parts.datatype + 4, 4);
    if ((parts.datatype[0] & 0x0FU) == kVariableLength) {  // HDF5 may size it for the file
        element = std::max<std::uint64_t>(element, 4 + sb.offsets + 4);
    }
    const bool huge = extent->elements != 0 && element > UINT64_MAX / extent->elements;
    if (huge || element * extent->elements > parts.left) {
        return what + ": its value of " + std::to_string(extent->elements) + " element(s) of " +
               std::to_string(element) + " bytes does not fit the " + std::to_string(parts.left) +
               " bytes after its dataspace";
    }
    return std::nullopt;
}

// An attribute message (versions 1-3) as H5O_attr_decode reads it: version, flags, the sizes of
// name (NUL included), datatype and dataspace, [encoding, version 3], then the three parts,
// each padded to 8 bytes in version 1, then the value.
std::optional<std::string> CheckAttribute(const std::uint8_t* data,
                                          std::uint64_t size,
                                          std::uint64_t where,
                                          const Superblock& sb) {
    constexpr std::uint8_t kSharedParts = 0x03;  // flags: datatype (1), dataspace (2) shared
    const std::string what = "attribute message " + At(where);
    if (size < 8) {
        return what + " is shorter than its 8-byte header";
    }
    const std::uint8_t version = data[0];
    if (version < 1 || version > 3) {
        return std::nullopt;  // HDF5 rejects the version before it reads a name
    }
    const std::uint64_t name = Decode(data + 2, 2);
    const std::uint64_t datatype = Decode(data + 4, 2);
    const std::uint64_t dataspace = Decode(data + 6, 2);
    const std::uint64_t header = version == 3 ? 9 : 8;
    const auto pad = [&](std::uint64_t n) { return version == 1 ? Align8(n) : n; };
    const std::uint64_t need = header + pad(name) + pad(datatype) + pad(dataspace);
    if (name == 0 || need > size) {
        return what + ": name " + std::to_string(name) + ", datatype " + std::to_string(datatype) +
               " and dataspace " + std::to_string(dataspace) + " bytes do not fit its " +
               std::to_string(size) + " bytes";
    }
    if (std::memchr(data + header, '\0', static_cast<std::size_t>(name)) == nullptr) {
        return what + ": the name is not NUL-terminated within its " + std::to_string(name) +
               " bytes";
    }
    if (version >= 2 && (data[1] & kSharedParts) != 0) {
        return std::nullopt;
    }
    const std::uint8_t* type = data + header + pad(name);
    return CheckValue({type, datatype, type + pad(datatype), dataspace, size - need}, sb, what);
}

struct Block {
    std::uint64_t at = 0;
    std::uint64_t size = 0;
};

}  // namespace

std::optional<std::string> FindCorruptAttributeMessages(std::uint64_t address,
                                                        std::uint64_t file_size,
                                                        const ReadAt& read) {
    const std::optional<Superblock> sb = ReadSuperblock(file_size, read);
    if (!sb) {
        return std::string(
            "no HDF5 superblock with sizes of offsets and lengths of 2, 4 or 8 at byte 0, so "
            "its object headers cannot be checked");
    }
    const std::uint64_t start = address;
    if (start > file_size || file_size - start < kV1PrefixBytes) {
        return "object header " + At(start) + " lies outside the file's " +
               std::to_string(file_size) + " bytes";
    }
    std::array<std::uint8_t, kV1PrefixBytes> prefix{};
    if (read(start, prefix.size(), prefix.data()) != prefix.size()) {
        return "object header " + At(start) + " cannot be read";
    }
    if (std::memcmp(prefix.data(), "OHDR", 4) == 0 || prefix[0] != 1) {
        return std::nullopt;  // version 2 (checksummed), or a version HDF5 rejects itself
    }
    std::vector<Block> blocks = {{start + kV1PrefixBytes, Decode(prefix.data() + 8, 4)}};
    std::set<std::uint64_t> seen = {blocks.front().at};
    std::vector<std::uint8_t> bytes;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        const Block block = blocks[b];
        if (block.size > kMaxBlockBytes || block.at > file_size ||
            block.size > file_size - block.at) {
            return "object header block " + At(block.at) + " of " + std::to_string(block.size) +
                   " bytes lies outside the file's " + std::to_string(file_size) + " bytes";
        }
        bytes.resize(static_cast<std::size_t>(block.size));
        if (read(block.at, bytes.size(), bytes.data()) != bytes.size()) {
            return "object header block " + At(block.at) + " cannot be read";
        }
        std::uint64_t pos = 0;
        while (block.size - pos >= kV1MessageHeaderBytes) {
            const auto type = static_cast<std::uint16_t>(Decode(&bytes[pos], 2));
            const std::uint64_t size = Decode(&bytes[pos + 2], 2);
            const std::uint8_t flags = bytes[pos + 4];
            const std::uint64_t data = pos + kV1MessageHeaderBytes;
            if (size > block.size - data) {
                return "object header message " + At(block.at + pos) + " of " +
                       std::to_string(size) + " bytes overruns its block";
            }
            if (type == kAttributeMessage && (flags & kMessageShared) == 0) {
                if (std::optional<std::string> why =
                        CheckAttribute(&bytes[data], size, block.at + pos, *sb)) {
                    return why;
                }
            } else if (type == kContinuationMessage && size >= sb->offsets + sb->lengths) {
                const Block next = {Decode(&bytes[data], sb->offsets),
                                    Decode(&bytes[data + sb->offsets], sb->lengths)};
                if (seen.insert(next.at).second) {
                    if (static_cast<int>(blocks.size()) > kMaxHeaderContinuations) {
                        return "object header " + At(start) + " has more than " +
                               std::to_string(kMaxHeaderContinuations) + " continuation blocks";
                    }
                    blocks.push_back(next);
                }
            }
            pos = data + size;
        }
    }
    return std::nullopt;
}

}  // namespace casmap::io::h5
