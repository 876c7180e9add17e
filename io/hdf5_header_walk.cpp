#include "casmap/io/hdf5_header_walk.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <set>

namespace casmap::io::h5 {
namespace {

constexpr std::array<std::uint8_t, 8> kSuperblockSignature = {0x89, 'H',  'D',  'F',
                                                              '\r', '\n', 0x1a, '\n'};
constexpr std::size_t kV1PrefixBytes = 16;          // 12 bytes and 4 of alignment
constexpr std::size_t kV1MessageHeaderBytes = 8;    // type 2, size 2, flags 1, reserved 3
constexpr std::size_t kV2PrefixMaxBytes = 34;       // "OHDR", version, flags, times, sizes
constexpr std::uint64_t kMaxBlockBytes = 1U << 24;  // a header chunk HDF5 would load (16 MiB)
constexpr int kMaxSharedHops = 4;  // a valid file needs 1 (attribute -> committed datatype)

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
            {start + at + bytes, DecodeLe(p + at, bytes)}, (flags & 0x04U) != 0 ? 6U : 4U, true};
    }
    if (p[0] != 1) {
        return std::nullopt;
    }
    return Layout{{start + kV1PrefixBytes, DecodeLe(p + 8, 4)}, kV1MessageHeaderBytes, false};
}

Resolved Resolve(const HeaderFile& file, const HeaderMessage& m, int hops, const std::string& what);

// A shared message (H5O_shared_decode): version 1: version, type, 6 reserved bytes, a length
// and the object header's address; versions 2-3: version, type (1: an 8-byte ID in the shared
// message heap, not followed here), address. HDF5 reads the
// first message of the same type in that object header (H5O__shared_read).
Resolved Follow(const HeaderFile& file, const HeaderMessage& m, int hops, const std::string& what) {
    constexpr std::uint8_t kInSharedHeap = 1;
    const std::uint8_t* p = m.data;
    const std::string part = m.type == kDatatypeMessage    ? "datatype"
                             : m.type == kDataspaceMessage ? "dataspace"
                                                           : "message";
    if (m.size < 2 || p[0] < 1 || p[0] > 3 || (p[0] >= 2 && p[1] == kInSharedHeap)) {
        return {};
    }
    const std::uint64_t at = p[0] == 1 ? 8 + file.sb.lengths : 2;
    if (m.size < at + file.sb.offsets) {
        return {what + ": its shared " + part + " reference of " + std::to_string(m.size) +
                    " bytes is shorter than the " + std::to_string(at + file.sb.offsets) +
                    " its version needs",
                false,
                {},
                m.at};
    }
    if (hops >= kMaxSharedHops) {
        return {what + ": its shared " + part + " is more than " + std::to_string(kMaxSharedHops) +
                    " references away",
                false,
                {},
                m.at};
    }
    Resolved r;
    bool taken = false;  // HDF5 takes the first message of the type
    const std::optional<std::string> walked =
        WalkHeader(file, DecodeLe(p + at, file.sb.offsets), true, [&](const HeaderMessage& target) {
            if (!taken && target.type == m.type) {
                taken = true;
                r = Resolve(file, target, hops + 1, what);
            }
            return std::optional<std::string>();
        });
    return walked ? Resolved{} : r;  // a header HDF5 cannot load either
}

Resolved Resolve(const HeaderFile& file,
                 const HeaderMessage& m,
                 int hops,
                 const std::string& what) {
    if ((m.flags & kMessageShared) != 0) {
        return Follow(file, m, hops, what);
    }
    return {std::nullopt, true, std::vector<std::uint8_t>(m.data, m.data + m.size), m.at};
}

}  // namespace

std::uint64_t DecodeLe(const std::uint8_t* p, std::size_t bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
        value |= static_cast<std::uint64_t>(p[i]) << (8U * i);
    }
    return value;
}

std::string AtByte(std::uint64_t offset) { return "at byte " + std::to_string(offset); }

// Superblock versions 0-1 keep the sizes at bytes 13-14 and the base address at byte 24
// (version 1: 28), versions 2-3 the sizes at bytes 9-10 and the base address at byte 12; the
// end-of-file address is the third address from the base address (base, free space or
// superblock extension, end of file).
std::optional<Superblock> ReadSuperblock(std::uint64_t file_size, const ReadAt& read) {
    std::array<std::uint8_t, 96> head{};
    const std::size_t got =
        static_cast<std::size_t>(std::min<std::uint64_t>(head.size(), file_size));
    if (got < 32 || read(0, got, head.data()) != got ||
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
    const std::size_t base = version == 0 ? 24 : version == 1 ? 28 : 12;
    const std::size_t eof = base + 2 * s.offsets;
    // Versions 0-1: base, free space, end of file, driver information, then the root group's
    // symbol table entry (link name offset, object header address); versions 2-3: base,
    // extension, end of file, root object header address.
    const std::size_t root = version <= 1 ? base + 5 * s.offsets : base + 3 * s.offsets;
    if (got < root + s.offsets) {
        return std::nullopt;  // HDF5 cannot read the superblock either
    }
    s.end_of_file = DecodeLe(&head[eof], s.offsets);
    s.root = DecodeLe(&head[root], s.offsets);
    return s;
}

std::optional<std::string> WalkHeader(const HeaderFile& file,
                                      std::uint64_t start,
                                      bool v2,
                                      const VisitMessage& visit) {
    if (start > file.size || file.size - start < kV1PrefixBytes) {
        return "object header " + AtByte(start) + " lies outside the file's " +
               std::to_string(file.size) + " bytes";
    }
    std::array<std::uint8_t, kV2PrefixMaxBytes> prefix{};
    const std::size_t got =
        static_cast<std::size_t>(std::min<std::uint64_t>(prefix.size(), file.size - start));
    if ((*file.read)(start, got, prefix.data()) != got) {
        return "object header " + AtByte(start) + " cannot be read";
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
            return "object header block " + AtByte(block.at) + " of " + std::to_string(block.size) +
                   " bytes lies outside the file's " + std::to_string(file.size) + " bytes";
        }
        bytes.resize(static_cast<std::size_t>(block.size));
        if ((*file.read)(block.at, bytes.size(), bytes.data()) != bytes.size()) {
            return "object header block " + AtByte(block.at) + " cannot be read";
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
            HeaderMessage m;
            m.type = static_cast<std::uint16_t>(DecodeLe(&bytes[pos], type_bytes));
            m.size = DecodeLe(&bytes[pos + type_bytes], 2);
            m.flags = bytes[pos + type_bytes + 2];
            m.at = block.at + pos;
            const std::uint64_t data = pos + layout->message_header;
            if (m.size > end - data) {
                return "object header message " + AtByte(m.at) + " of " + std::to_string(m.size) +
                       " bytes overruns its block";
            }
            m.data = &bytes[data];
            if (std::optional<std::string> why = visit(m)) {
                return why;
            }
            if (m.type == kContinuationMessage && m.size >= file.sb.offsets + file.sb.lengths) {
                const Block next = {DecodeLe(m.data, file.sb.offsets),
                                    DecodeLe(m.data + file.sb.offsets, file.sb.lengths)};
                if (seen.insert(next.at).second) {
                    if (static_cast<int>(blocks.size()) > kMaxHeaderContinuations) {
                        return "object header " + AtByte(start) + " has more than " +
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

std::optional<Extent> DecodeExtent(const std::uint8_t* p, std::uint64_t size, std::size_t lengths) {
    constexpr std::uint8_t kMaxRank = 32;       // H5S_MAX_RANK
    constexpr std::uint8_t kNullDataspace = 2;  // version 2 type byte
    constexpr std::uint8_t kMaximaPresent = 1;  // flags
    if (size < 4 || p[0] < 1 || p[0] > 2 || p[1] > kMaxRank) {
        return std::nullopt;  // HDF5 rejects the version or rank before it reads sizes
    }
    Extent e;
    e.rank = p[1];
    const bool maxima = (p[2] & kMaximaPresent) != 0;
    e.need = (p[0] == 1 ? 8 : 4) + std::uint64_t{e.rank} * lengths * (maxima ? 2 : 1);
    if (e.need > size) {
        return e;
    }
    const std::uint8_t* dims = p + (p[0] == 1 ? 8 : 4);
    e.elements = p[0] == 2 && p[3] == kNullDataspace ? 0 : 1;
    const bool null = e.elements == 0;
    for (std::uint8_t k = 0; k < e.rank; ++k) {
        const std::uint64_t n = DecodeLe(dims + std::size_t{k} * lengths, lengths);
        e.sizes.push_back(n);
        if (maxima) {
            e.maxima.push_back(DecodeLe(dims + (std::size_t{e.rank} + k) * lengths, lengths));
        }
        if (!null) {
            e.elements = n != 0 && e.elements > UINT64_MAX / n ? UINT64_MAX : e.elements * n;
        }
    }
    return e;
}

std::optional<std::string> FindCorruptHeaderBlocks(std::optional<std::uint64_t> address,
                                                   std::uint64_t file_size,
                                                   const ReadAt& read) {
    const std::optional<Superblock> sb = ReadSuperblock(file_size, read);
    if (!sb) {
        return std::nullopt;  // H5Fopen rejects the file, or the walks that need it say so
    }
    const HeaderFile file{*sb, file_size, &read};
    return WalkHeader(file, address.value_or(sb->root), true,
                      [](const HeaderMessage&) { return std::optional<std::string>(); });
}

Resolved ResolveMessage(const HeaderFile& file, const HeaderMessage& m, const std::string& what) {
    return Resolve(file, m, 0, what);
}

}  // namespace casmap::io::h5
