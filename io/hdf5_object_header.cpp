#include "casmap/io/hdf5_object_header.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <set>
#include <vector>

#include "casmap/io/hdf5_datatype_check.hpp"

namespace casmap::io::h5 {
namespace {

constexpr std::array<std::uint8_t, 8> kSuperblockSignature = {0x89, 'H',  'D',  'F',
                                                              '\r', '\n', 0x1a, '\n'};
constexpr std::uint16_t kDataspaceMessage = 0x0001;
constexpr std::uint16_t kDatatypeMessage = 0x0003;
constexpr std::uint16_t kAttributeMessage = 0x000C;
constexpr std::uint16_t kContinuationMessage = 0x0010;
constexpr std::uint8_t kMessageShared = 0x02;       // the message holds a shared reference
constexpr std::size_t kV1PrefixBytes = 16;          // 12 bytes and 4 of alignment
constexpr std::size_t kV1MessageHeaderBytes = 8;    // type 2, size 2, flags 1, reserved 3
constexpr std::size_t kV2PrefixMaxBytes = 34;       // "OHDR", version, flags, times, sizes
constexpr std::uint64_t kMaxBlockBytes = 1U << 24;  // a header chunk HDF5 would load (16 MiB)
constexpr int kMaxSharedHops = 4;  // a valid file needs 1 (attribute -> committed datatype)

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

struct File {
    Superblock sb;
    std::uint64_t size = 0;
    const ReadAt* read = nullptr;
};

struct Message {
    std::uint16_t type = 0;
    std::uint8_t flags = 0;
    const std::uint8_t* data = nullptr;
    std::uint64_t size = 0;
    std::uint64_t at = 0;  // where its message header starts in the file
};
using Visit = std::function<std::optional<std::string>(const Message&)>;

struct Block {
    std::uint64_t at = 0;
    std::uint64_t size = 0;
};

// How a header lays out its messages: version 1 (16-byte prefix, 8-byte message headers) or
// version 2 ("OHDR", version 2, flags; times and attribute phase change values if flagged; the
// first chunk's size in 1, 2, 4 or 8 bytes; message headers of type 1, size 2, flags 1 and a
// creation order 2 if flagged; continuation blocks "OCHK" ... checksum).
struct Layout {
    Block first;
    std::size_t message_header = kV1MessageHeaderBytes;
    bool v2 = false;
};

std::optional<Layout> ReadLayout(const std::uint8_t* p, std::size_t got, std::uint64_t start) {
    if (std::memcmp(p, "OHDR", 4) == 0) {
        const std::uint8_t flags = p[5];
        const std::size_t at = 6 + ((flags & 0x20U) != 0 ? 16 : 0) + ((flags & 0x10U) != 0 ? 4 : 0);
        const std::size_t bytes = std::size_t{1} << (flags & 0x03U);
        if (p[4] != 2 || got < at + bytes) {
            return std::nullopt;  // HDF5 rejects it
        }
        return Layout{
            {start + at + bytes, Decode(p + at, bytes)}, (flags & 0x04U) != 0 ? 6U : 4U, true};
    }
    if (p[0] != 1) {
        return std::nullopt;
    }
    return Layout{{start + kV1PrefixBytes, Decode(p + 8, 4)}, kV1MessageHeaderBytes, false};
}

// Walks the header at `start` the way HDF5 lays it out (the first chunk and each continuation
// block) and calls `visit` on each message; returns the first reason `visit` or the walk gives.
// A version 2 header is walked only if `v2` (HDF5 checks its checksums; casmap reads it only
// to find what a shared reference points at).
std::optional<std::string> Walk(const File& file,
                                std::uint64_t start,
                                bool v2,
                                const Visit& visit) {
    if (start > file.size || file.size - start < kV1PrefixBytes) {
        return "object header " + At(start) + " lies outside the file's " +
               std::to_string(file.size) + " bytes";
    }
    std::array<std::uint8_t, kV2PrefixMaxBytes> prefix{};
    const std::size_t got =
        static_cast<std::size_t>(std::min<std::uint64_t>(prefix.size(), file.size - start));
    if ((*file.read)(start, got, prefix.data()) != got) {
        return "object header " + At(start) + " cannot be read";
    }
    const std::optional<Layout> layout = ReadLayout(prefix.data(), got, start);
    if (!layout || (layout->v2 && !v2)) {
        return std::nullopt;  // a version HDF5 rejects itself, or version 2 (checksummed)
    }
    std::vector<Block> blocks = {layout->first};
    std::set<std::uint64_t> seen = {blocks.front().at};
    std::vector<std::uint8_t> bytes;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        const Block block = blocks[b];
        if (block.size > kMaxBlockBytes || block.at > file.size ||
            block.size > file.size - block.at) {
            return "object header block " + At(block.at) + " of " + std::to_string(block.size) +
                   " bytes lies outside the file's " + std::to_string(file.size) + " bytes";
        }
        bytes.resize(static_cast<std::size_t>(block.size));
        if ((*file.read)(block.at, bytes.size(), bytes.data()) != bytes.size()) {
            return "object header block " + At(block.at) + " cannot be read";
        }
        std::uint64_t pos = 0;
        std::uint64_t end = block.size;
        if (layout->v2 && b > 0) {  // "OCHK", messages, checksum
            if (block.size < 8 || std::memcmp(bytes.data(), "OCHK", 4) != 0) {
                continue;
            }
            pos = 4;
            end -= 4;
        }
        while (end - pos >= layout->message_header) {
            const std::size_t type_bytes = layout->v2 ? 1 : 2;
            Message m;
            m.type = static_cast<std::uint16_t>(Decode(&bytes[pos], type_bytes));
            m.size = Decode(&bytes[pos + type_bytes], 2);
            m.flags = bytes[pos + type_bytes + 2];
            m.at = block.at + pos;
            const std::uint64_t data = pos + layout->message_header;
            if (m.size > end - data) {
                return "object header message " + At(m.at) + " of " + std::to_string(m.size) +
                       " bytes overruns its block";
            }
            m.data = &bytes[data];
            if (std::optional<std::string> why = visit(m)) {
                return why;
            }
            if (m.type == kContinuationMessage && m.size >= file.sb.offsets + file.sb.lengths) {
                const Block next = {Decode(m.data, file.sb.offsets),
                                    Decode(m.data + file.sb.offsets, file.sb.lengths)};
                if (seen.insert(next.at).second) {
                    if (static_cast<int>(blocks.size()) > kMaxHeaderContinuations) {
                        return "object header " + At(start) + " has more than " +
                               std::to_string(kMaxHeaderContinuations) + " continuation blocks";
                    }
                    blocks.push_back(next);
                }
            }
            pos = data + m.size;
        }
    }
    return std::nullopt;
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
// message's (fuzz finding, docs/fuzzing.md). `datatype` and `dataspace` are the messages HDF5
// decodes (the attribute's own parts, or the messages a shared reference points at).
struct Parts {
    std::vector<std::uint8_t> datatype;
    std::vector<std::uint8_t> dataspace;
    std::uint64_t left = 0;  // the message's bytes after the dataspace (and its padding)
};

std::optional<std::string> CheckValue(const Parts& parts,
                                      const Superblock& sb,
                                      const std::string& what) {
    constexpr std::uint64_t kDatatypeHeaderBytes = 8;  // class and version 4, size 4
    constexpr std::uint8_t kVariableLength = 9;        // datatype class
    const std::optional<Extent> extent =
        DecodeExtent(parts.dataspace.data(), parts.dataspace.size(), sb.lengths);
    if (!extent) {
        return std::nullopt;
    }
    if (extent->need > parts.dataspace.size()) {
        return what + ": its dataspace needs " + std::to_string(extent->need) +
               " bytes for its rank but has " + std::to_string(parts.dataspace.size());
    }
    if (parts.datatype.size() < kDatatypeHeaderBytes) {
        return what + ": its datatype of " + std::to_string(parts.datatype.size()) +
               " bytes is shorter than a datatype's 8-byte header";
    }
    if (std::optional<std::string> why =
            CheckDatatypeEncoding(parts.datatype.data(), parts.datatype.size())) {
        return what + ": " + *why;
    }
    std::uint64_t element = Decode(parts.datatype.data() + 4, 4);
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

// A datatype or dataspace message, or the one a shared reference points at.
struct Resolved {
    std::optional<std::string> error;
    bool found = false;  // false: HDF5 cannot read it either, or casmap does not follow it
    std::vector<std::uint8_t> bytes;
};

Resolved Resolve(const File& file, const Message& m, int hops, const std::string& what);

// A shared message (H5O_shared_decode): version 1: version, type, 6 reserved bytes, a length
// and the object header's address; versions 2-3: version, type (1: an 8-byte ID in the shared
// message heap, not followed here), address. HDF5 reads the
// first message of the same type in that object header (H5O__shared_read).
Resolved Follow(const File& file, const Message& m, int hops, const std::string& what) {
    constexpr std::uint8_t kInSharedHeap = 1;
    const std::uint8_t* p = m.data;
    const std::string part = m.type == kDatatypeMessage ? "datatype" : "dataspace";
    if (m.size < 2 || p[0] < 1 || p[0] > 3 || (p[0] >= 2 && p[1] == kInSharedHeap)) {
        return {};
    }
    const std::uint64_t at = p[0] == 1 ? 8 + file.sb.lengths : 2;
    if (m.size < at + file.sb.offsets) {
        return {what + ": its shared " + part + " reference of " + std::to_string(m.size) +
                    " bytes is shorter than the " + std::to_string(at + file.sb.offsets) +
                    " its version needs",
                false,
                {}};
    }
    if (hops >= kMaxSharedHops) {
        return {what + ": its shared " + part + " is more than " + std::to_string(kMaxSharedHops) +
                    " references away",
                false,
                {}};
    }
    Resolved r;
    bool taken = false;  // HDF5 takes the first message of the type
    const std::optional<std::string> walked =
        Walk(file, Decode(p + at, file.sb.offsets), true, [&](const Message& target) {
            if (!taken && target.type == m.type) {
                taken = true;
                r = Resolve(file, target, hops + 1, what);
            }
            return std::optional<std::string>();
        });
    return walked ? Resolved{} : r;  // a header HDF5 cannot load either
}

Resolved Resolve(const File& file, const Message& m, int hops, const std::string& what) {
    if ((m.flags & kMessageShared) != 0) {
        return Follow(file, m, hops, what);
    }
    return {std::nullopt, true, std::vector<std::uint8_t>(m.data, m.data + m.size)};
}

// An attribute message (versions 1-3) as H5O_attr_decode reads it: version, flags (versions
// 2-3: datatype (1) and dataspace (2) shared), the sizes of name (NUL included), datatype and
// dataspace, [encoding, version 3], then the three parts, each padded to 8 bytes in version 1,
// then the value.
std::optional<std::string> CheckAttribute(const File& file, const Message& m) {
    const std::uint8_t* data = m.data;
    const std::string what = "attribute message " + At(m.at);
    if (m.size < 8) {
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
    if (name == 0 || need > m.size) {
        return what + ": name " + std::to_string(name) + ", datatype " + std::to_string(datatype) +
               " and dataspace " + std::to_string(dataspace) + " bytes do not fit its " +
               std::to_string(m.size) + " bytes";
    }
    if (std::memchr(data + header, '\0', static_cast<std::size_t>(name)) == nullptr) {
        return what + ": the name is not NUL-terminated within its " + std::to_string(name) +
               " bytes";
    }
    const std::uint8_t shared = version >= 2 ? data[1] : 0;
    const std::uint8_t* type = data + header + pad(name);
    const Resolved t =
        Resolve(file,
                {kDatatypeMessage, (shared & 1U) != 0 ? kMessageShared : std::uint8_t{0}, type,
                 datatype, m.at},
                0, what);
    const Resolved s =
        Resolve(file,
                {kDataspaceMessage, (shared & 2U) != 0 ? kMessageShared : std::uint8_t{0},
                 type + pad(datatype), dataspace, m.at},
                0, what);
    if (t.error || s.error) {
        return t.error ? t.error : s.error;
    }
    if (!t.found || !s.found) {
        return std::nullopt;
    }
    return CheckValue({t.bytes, s.bytes, m.size - need}, file.sb, what);
}

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
    const File file{*sb, file_size, &read};
    return Walk(file, address, false, [&](const Message& m) -> std::optional<std::string> {
        if (m.type == kAttributeMessage && (m.flags & kMessageShared) == 0) {
            return CheckAttribute(file, m);
        }
        return std::nullopt;
    });
}

}  // namespace casmap::io::h5
