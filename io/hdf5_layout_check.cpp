#include "casmap/io/hdf5_layout_check.hpp"

#include <vector>

#include "casmap/io/hdf5_message_cursor.hpp"

namespace casmap::io::h5 {
namespace {

constexpr std::uint8_t kMaxLayoutDims = 33;  // H5O_LAYOUT_NDIMS: H5S_MAX_RANK + 1

// H5O__layout_decode's chunk rules and H5D__chunk_init's use of the dimensions: one per
// dataspace dimension and one for the element, none 0 (HDF5 checks that only for version 3).
// Then what H5D__chunk_construct makes every chunked dataset HDF5 writes satisfy, and 1.10.8
// does not check when it opens one: the last dimension is the datatype's size (HDF5 sizes its
// chunk buffers from the dimensions but copies elements of the datatype's size: fuzz finding,
// a 14-byte float in 4-byte chunk elements read past the buffer), and no dimension exceeds the
// dataspace's fixed maximum (its size when it stores none; a chunk of 46 336 columns for 181
// made HDF5 copy past the chunk it inflated: fuzz finding).
bool CheckChunk(Cursor& c, const std::vector<std::uint64_t>& dims, const LayoutContext& ctx) {
    if (ctx.extent && dims.size() != std::size_t{ctx.extent->rank} + 1) {
        return c.Fail("its chunk has " + std::to_string(dims.size()) +
                      " dimensions but a dataspace of rank " + std::to_string(ctx.extent->rank) +
                      " needs " + std::to_string(ctx.extent->rank + 1));
    }
    for (std::size_t k = 0; k < dims.size(); ++k) {
        if (dims[k] == 0) {
            return c.Fail("its chunk dimension " + std::to_string(k) + " is 0");
        }
    }
    if (!ctx.extent) {
        return true;
    }
    if (ctx.type_size && dims.back() != *ctx.type_size) {
        return c.Fail("its chunk's element dimension of " + std::to_string(dims.back()) +
                      " bytes is not the datatype's size of " + std::to_string(*ctx.type_size) +
                      " bytes");
    }
    const std::vector<std::uint64_t>& fixed =
        ctx.extent->maxima.empty() ? ctx.extent->sizes : ctx.extent->maxima;
    for (std::size_t k = 0; k + 1 < dims.size(); ++k) {
        if (fixed[k] != AllOnes(ctx.sb->lengths) && dims[k] > fixed[k]) {
            return c.Fail("its chunk dimension " + std::to_string(k) + " of " +
                          std::to_string(dims[k]) + " exceeds the dataspace's fixed maximum " +
                          std::to_string(fixed[k]));
        }
    }
    return true;
}

// H5D__contig_check's rule: contiguous data ends within the end of allocation (an undefined
// address, all bits set, means no data written yet).
bool CheckContiguous(Cursor& c,
                     std::uint64_t address,
                     std::uint64_t size,
                     const LayoutContext& ctx) {
    const std::uint64_t eoa = ctx.sb->end_of_file;
    if (address != AllOnes(ctx.sb->offsets) && (address > eoa || size > eoa - address)) {
        return c.Fail("its contiguous data at byte " + std::to_string(address) + " of " +
                      std::to_string(size) + " bytes ends past the file's end-of-file address " +
                      std::to_string(eoa));
    }
    return true;
}

// H5D__contig_init and H5D__compact_init size a dataset's data as elements x datatype size and
// H5Dread copies that many bytes; data stored with another size means the datatype, dataspace
// or layout is corrupt (fuzz findings: a float of 2 113 929 224 bytes made HDF5 allocate 2 GB
// for 48 stored bytes; a string of 31 bytes in 0 bytes of compact data, whose buffer HDF5 left
// null, made it copy from address 0).
bool CheckDataSize(Cursor& c, const char* storage, std::uint64_t size, const LayoutContext& ctx) {
    const bool known =
        ctx.extent && ctx.type_size && ctx.extent->elements != UINT64_MAX &&
        (ctx.extent->elements == 0 || *ctx.type_size <= UINT64_MAX / ctx.extent->elements);
    if (known && size != ctx.extent->elements * *ctx.type_size) {
        return c.Fail(std::string("its ") + storage + " data of " + std::to_string(size) +
                      " bytes is not the " + std::to_string(ctx.extent->elements) +
                      " element(s) of " + std::to_string(*ctx.type_size) +
                      " bytes its dataspace and datatype say");
    }
    return true;
}

bool CheckCompact(Cursor& c, std::uint64_t size, const LayoutContext& ctx) {
    if (size > c.left()) {
        return c.Fail("its compact data of " + std::to_string(size) + " bytes does not fit the " +
                      std::to_string(c.left()) + " bytes after its size");
    }
    return c.Skip(size, "compact data") && CheckDataSize(c, "compact", size, ctx);
}

// Layout versions 1-2 (H5O__layout_decode): dimensionality (1-33), class, 5 reserved bytes, an
// address unless compact, 4 bytes per dimension, then for compact a 4-byte size and the data.
// The contiguous size is the dataspace's elements times the datatype's size.
bool LayoutV1(Cursor& c, const LayoutContext& ctx) {
    const std::optional<std::uint64_t> ndims = c.Get(1, "dimensionality");
    if (!ndims || *ndims == 0 || *ndims > kMaxLayoutDims) {
        return false;  // HDF5: dimensionality is out of range
    }
    const std::optional<std::uint64_t> cls = c.Get(1, "layout class");
    if (cls && *cls > 2) {  // HDF5 only asserts it
        return c.Fail("its layout class " + std::to_string(*cls) +
                      " is not compact (0), contiguous (1) or chunked (2)");
    }
    if (!cls || !c.Skip(5, "reserved bytes")) {
        return false;
    }
    std::optional<std::uint64_t> address = 0;
    if (*cls != 0 && !(address = c.Get(ctx.sb->offsets, "address"))) {
        return false;
    }
    std::vector<std::uint64_t> dims;
    for (std::uint64_t k = 0; k < *ndims; ++k) {
        const std::optional<std::uint64_t> d = c.Get(4, "dimension sizes");
        if (!d) {
            return false;
        }
        dims.push_back(*d);
    }
    if (*cls == 0) {
        const std::optional<std::uint64_t> size = c.Get(4, "compact data size");
        return size && CheckCompact(c, *size, ctx);
    }
    if (*cls == 2) {
        return CheckChunk(c, dims, ctx);
    }
    const bool known =
        ctx.extent && ctx.type_size && ctx.extent->elements != UINT64_MAX &&
        (ctx.extent->elements == 0 || *ctx.type_size <= UINT64_MAX / ctx.extent->elements);
    return CheckContiguous(c, *address, known ? ctx.extent->elements * *ctx.type_size : 0, ctx);
}

// Version 4 chunk indexes (H5D_chunk_index_t): the bytes of creation parameters each has.
std::optional<std::uint64_t> IndexBytes(std::uint64_t index,
                                        std::uint64_t flags,
                                        std::size_t lengths) {
    constexpr std::uint64_t kSingleChunkFiltered = 0x02;
    switch (index) {
        case 1:  // single chunk: its filtered size and filter mask, if filtered
            return (flags & kSingleChunkFiltered) != 0 ? lengths + 4 : 0;
        case 2:  // implicit
            return 0;
        case 3:  // fixed array: page bits
            return 1;
        case 4:  // extensible array: 5 parameters
            return 5;
        case 5:  // version 2 B-tree: node size 4, split and merge percent
            return 6;
        default:
            return std::nullopt;  // HDF5: v1 B-tree in a v4 message, or an unknown index type
    }
}

// Layout versions 3-4 (H5O__layout_decode): class; compact: 2-byte size and the data;
// contiguous: address and size; chunked version 3: dimensionality (at most 33), address,
// 4 bytes per dimension; version 4: flags, dimensionality, bytes per dimension (1-8), the
// dimensions, the index type, its parameters, the address; virtual (version 4): heap address
// and index.
bool LayoutV3(Cursor& c, std::uint64_t version, const LayoutContext& ctx) {
    const std::optional<std::uint64_t> cls = c.Get(1, "layout class");
    if (!cls) {
        return false;
    }
    if (*cls == 0) {
        const std::optional<std::uint64_t> size = c.Get(2, "compact data size");
        return size && CheckCompact(c, *size, ctx);
    }
    if (*cls == 1) {
        const std::optional<std::uint64_t> address = c.Get(ctx.sb->offsets, "address");
        const std::optional<std::uint64_t> size =
            address ? c.Get(ctx.sb->lengths, "size") : std::nullopt;
        return size && CheckContiguous(c, *address, *size, ctx) &&
               CheckDataSize(c, "contiguous", *size, ctx);
    }
    if (*cls == 3) {
        return version >= 4 && c.Skip(ctx.sb->offsets + 4, "virtual dataset heap ID");
    }
    if (*cls != 2) {
        return false;  // HDF5: invalid layout class
    }
    constexpr std::uint64_t kKnownChunkFlags = 0x03;
    std::uint64_t flags = 0;
    if (version >= 4) {
        const std::optional<std::uint64_t> f = c.Get(1, "chunk flags");
        if (!f || (*f & ~kKnownChunkFlags) != 0) {
            return false;  // HDF5: bad flag value
        }
        flags = *f;
    }
    const std::optional<std::uint64_t> ndims = c.Get(1, "dimensionality");
    if (!ndims || *ndims > kMaxLayoutDims) {
        return false;  // HDF5: dimensionality is too large
    }
    std::size_t width = 4;
    if (version >= 4) {
        const std::optional<std::uint64_t> w = c.Get(1, "bytes per chunk dimension");
        if (!w || *w == 0 || *w > 8) {
            return false;  // HDF5: encoded chunk dimension size is too large
        }
        width = static_cast<std::size_t>(*w);
    } else if (!c.Skip(ctx.sb->offsets, "address")) {
        return false;
    }
    std::vector<std::uint64_t> dims;
    for (std::uint64_t k = 0; k < *ndims; ++k) {
        const std::optional<std::uint64_t> d = c.Get(width, "chunk dimensions");
        if (!d) {
            return false;
        }
        dims.push_back(*d);
    }
    if (version >= 4) {
        const std::optional<std::uint64_t> index = c.Get(1, "chunk index type");
        const std::optional<std::uint64_t> params =
            index ? IndexBytes(*index, flags, ctx.sb->lengths) : std::nullopt;
        if (!params || !c.Skip(*params, "chunk index parameters") ||
            !c.Skip(ctx.sb->offsets, "address")) {
            return false;
        }
    }
    return CheckChunk(c, dims, ctx);
}

}  // namespace

std::uint64_t AllOnes(std::size_t bytes) {
    return bytes >= 8 ? UINT64_MAX : (std::uint64_t{1} << (8U * bytes)) - 1;
}

std::optional<std::string> CheckLayout(const Resolved& m, const LayoutContext& ctx) {
    Cursor c(m.bytes, "layout message " + AtByte(m.at));
    const std::optional<std::uint64_t> version = c.Get(1, "version");
    if (version && *version >= 1 && *version <= 4) {  // else HDF5: bad version number
        (void)(*version < 3 ? LayoutV1(c, ctx) : LayoutV3(c, *version, ctx));
    }
    return c.error();
}

}  // namespace casmap::io::h5
