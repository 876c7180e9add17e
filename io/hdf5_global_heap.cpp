#include "casmap/io/hdf5_global_heap.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace casmap::io::h5 {
namespace {

constexpr std::array<std::uint8_t, 8> kSuperblockSignature = {0x89, 'H',  'D',  'F',
                                                              '\r', '\n', 0x1a, '\n'};
constexpr std::array<std::uint8_t, 4> kCollectionSignature = {'G', 'C', 'O', 'L'};
constexpr std::uint8_t kCollectionVersion = 1;
constexpr std::uint64_t kMinCollectionBytes = 4096;  // H5HG_MINSIZE
constexpr std::uint64_t kAlignment = 8;              // H5HG_ALIGNMENT
constexpr std::size_t kScanBlockBytes = std::size_t{1} << 20;

std::uint64_t DecodeLength(const std::uint8_t* p, std::size_t bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
        value |= static_cast<std::uint64_t>(p[i]) << (8U * i);
    }
    return value;
}

// The superblock's "size of lengths" (2, 4 or 8 bytes): the width of a collection's size and
// of each object's size.
std::optional<std::size_t> SizeOfLengths(std::uint64_t file_size, const ReadAt& read) {
    std::array<std::uint8_t, 16> head{};
    if (file_size < head.size() || read(0, head.size(), head.data()) != head.size() ||
        !std::equal(kSuperblockSignature.begin(), kSuperblockSignature.end(), head.begin())) {
        return std::nullopt;
    }
    const std::uint8_t version = head[8];
    const std::size_t lengths = version <= 1 ? head[14] : version <= 3 ? head[10] : 0;
    if (lengths != 2 && lengths != 4 && lengths != 8) {
        return std::nullopt;
    }
    return lengths;
}

std::string At(std::uint64_t offset) { return "at byte " + std::to_string(offset); }

// Walks one collection as H5HG__cache_heap_deserialize does, with bounds it lacks.
std::optional<std::string> CheckCollection(std::uint64_t at,
                                           std::uint64_t file_size,
                                           std::size_t lengths,
                                           const ReadAt& read) {
    const std::size_t header = 8 + lengths;      // H5HG_SIZEOF_HDR
    const std::size_t obj_header = 8 + lengths;  // H5HG_SIZEOF_OBJHDR
    std::array<std::uint8_t, 16> head{};
    if (file_size - at < header || read(at, header, head.data()) != header) {
        return "global heap collection " + At(at) + " is cut off by the end of the file";
    }
    const std::uint64_t size = DecodeLength(head.data() + 8, lengths);
    if (size < kMinCollectionBytes || size > kMaxGlobalHeapCollectionBytes ||
        size > file_size - at) {
        return "global heap collection " + At(at) + " declares " + std::to_string(size) +
               " bytes (must be 4096.." + std::to_string(kMaxGlobalHeapCollectionBytes) +
               " and inside the file's " + std::to_string(file_size) + " bytes)";
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (read(at, bytes.size(), bytes.data()) != bytes.size()) {
        return "global heap collection " + At(at) + " cannot be read";
    }
    std::uint64_t pos = header;
    while (pos < size) {
        if (size - pos < obj_header) {
            break;  // HDF5 takes a tail shorter than an object header as free space
        }
        const std::uint64_t index = DecodeLength(bytes.data() + pos, 2);
        const std::uint64_t object_size = DecodeLength(bytes.data() + pos + 8, lengths);
        const std::uint64_t room = size - pos;
        // HDF5 steps by the padded object (index > 0) or by the free space's size (index 0,
        // which includes its header): it must move forward and stay inside the collection.
        const bool fits = index > 0 ? object_size <= room - obj_header
                                    : object_size >= obj_header && object_size <= room;
        if (!fits) {
            const std::string what =
                index > 0 ? "object " + std::to_string(index) + " of " : "free space of ";
            return "global heap collection " + At(at) + ": " + what + std::to_string(object_size) +
                   " bytes " +
                   (index > 0 ? "overruns the " + std::to_string(room) + " bytes left"
                              : "(must be " + std::to_string(obj_header) + ".." +
                                    std::to_string(room) + ", the bytes left)");
        }
        const std::uint64_t need =
            index > 0 ? obj_header + (object_size + kAlignment - 1) / kAlignment * kAlignment
                      : object_size;
        pos += need;
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> FindCorruptGlobalHeap(std::uint64_t file_size, const ReadAt& read) {
    const std::optional<std::size_t> lengths = SizeOfLengths(file_size, read);
    if (!lengths) {
        return std::string(
            "no HDF5 superblock with a size of lengths of 2, 4 or 8 at byte 0, so "
            "its global heap cannot be checked");
    }
    // Scan in blocks that overlap by the signature and version bytes less one, so a signature
    // across a block boundary is found once.
    constexpr std::size_t kProbe = kCollectionSignature.size() + 1;
    std::vector<std::uint8_t> block(kScanBlockBytes);
    for (std::uint64_t start = 0; start < file_size;) {
        const std::size_t got = read(start, block.size(), block.data());
        if (got < kProbe) {
            break;
        }
        for (std::size_t i = 0; i + kProbe <= got; ++i) {
            if (block[i] == 'G' &&
                std::memcmp(&block[i], kCollectionSignature.data(), kCollectionSignature.size()) ==
                    0 &&
                block[i + kCollectionSignature.size()] == kCollectionVersion) {
                if (std::optional<std::string> why =
                        CheckCollection(start + i, file_size, *lengths, read)) {
                    return why;
                }
            }
        }
        if (got < block.size()) {
            break;
        }
        start += got - (kProbe - 1);
    }
    return std::nullopt;
}

}  // namespace casmap::io::h5
