#include "casmap/io/hdf5_dataset_header.hpp"

#include <cstring>
#include <map>
#include <vector>

#include "casmap/io/hdf5_datatype_check.hpp"
#include "casmap/io/hdf5_header_walk.hpp"
#include "casmap/io/hdf5_layout_check.hpp"
#include "casmap/io/hdf5_message_cursor.hpp"

namespace casmap::io::h5 {
namespace {

constexpr std::uint64_t kDatatypeHeaderBytes = 8;  // class and version 4, size 4
constexpr std::uint8_t kMaxFilters = 32;           // H5Z_MAX_NFILTERS
constexpr std::uint16_t kFirstNamedFilter = 256;   // H5Z_FILTER_RESERVED: ids that carry a name

std::string MessageName(std::uint16_t type) {
    switch (type) {
        case kDatatypeMessage:
            return "datatype";
        case kDataspaceMessage:
            return "dataspace";
        case kLayoutMessage:
            return "layout";
        case kFilterPipelineMessage:
            return "filter pipeline";
        case kFillValueMessage:
        case kOldFillValueMessage:
            return "fill value";
        default:
            return "external file list";
    }
}

// H5O__pline_decode: version (1-2), the number of filters (at most 32), version 1 six reserved
// bytes; per filter its id, a name length (version 1, or an id of 256 and up), flags, the
// number of client data values, the name (version 1 padded to 8 bytes, which HDF5 checks),
// 4 bytes per value and, version 1 with an odd number, 4 bytes of padding. HDF5 takes the
// name's length with strlen from the name's first byte.
std::optional<std::string> CheckPipeline(const Resolved& m) {
    Cursor c(m.bytes, "filter pipeline message " + AtByte(m.at));
    const std::optional<std::uint64_t> version = c.Get(1, "version");
    const std::optional<std::uint64_t> filters =
        version && *version >= 1 && *version <= 2 ? c.Get(1, "number of filters") : std::nullopt;
    if (!filters || *filters > kMaxFilters || (*version == 1 && !c.Skip(6, "reserved bytes"))) {
        return c.error();  // else HDF5 rejects the version or the number of filters
    }
    for (std::uint64_t i = 0; i < *filters; ++i) {
        const std::string filter = "filter " + std::to_string(i);
        const std::optional<std::uint64_t> id = c.Get(2, filter + " id");
        std::optional<std::uint64_t> name = 0;
        if (id && (*version == 1 || *id >= kFirstNamedFilter)) {
            name = c.Get(2, filter + " name length");
        }
        if (!id || !name || (*version == 1 && *name % 8 != 0)) {
            return c.error();  // HDF5: filter name length is not a multiple of eight
        }
        const std::optional<std::uint64_t> values =
            c.Skip(2, filter + " flags") ? c.Get(2, filter + " number of values") : std::nullopt;
        if (!values) {
            return c.error();
        }
        if (*name > 0) {
            if (*name > c.left()) {
                c.Fail(filter + "'s name of " + std::to_string(*name) + " bytes at byte " +
                       std::to_string(c.pos()) + " overruns its " + std::to_string(m.bytes.size()) +
                       " bytes");
                return c.error();
            }
            if (std::memchr(c.here(), '\0', static_cast<std::size_t>(*name)) == nullptr) {
                c.Fail(filter + "'s name is not NUL-terminated within its " +
                       std::to_string(*name) + " bytes");
                return c.error();
            }
            (void)c.Skip(*name, filter + " name");
        }
        const std::uint64_t data = 4 * *values + (*version == 1 && *values % 2 != 0 ? 4 : 0);
        if (data > c.left()) {
            c.Fail(filter + "'s " + std::to_string(*values) + " client data values at byte " +
                   std::to_string(c.pos()) + " overrun its " + std::to_string(m.bytes.size()) +
                   " bytes");
            return c.error();
        }
        (void)c.Skip(data, filter + " client data");
    }
    return std::nullopt;
}

// H5O_fill_new_decode (versions 1-2: allocation time, fill time, "defined", then if defined a
// signed 4-byte size and the value; version 3: flags, then with "have value" (0x20) a 4-byte
// size and the value) and H5O_fill_old_decode (a 4-byte size and the value): HDF5 copies the
// value with memcpy.
std::optional<std::string> CheckFill(const Resolved& m, std::uint16_t type) {
    constexpr std::uint64_t kKnownFlags = 0x3F;
    constexpr std::uint64_t kUndefinedValue = 0x10;
    constexpr std::uint64_t kHaveValue = 0x20;
    Cursor c(m.bytes, "fill value message " + AtByte(m.at));
    std::optional<std::uint64_t> size;
    if (type == kOldFillValueMessage) {
        size = c.Get(4, "size");
    } else {
        const std::optional<std::uint64_t> version = c.Get(1, "version");
        if (!version || *version < 1 || *version > 3) {
            return c.error();  // HDF5: bad version number
        }
        if (*version < 3) {
            const std::optional<std::uint64_t> defined =
                c.Skip(2, "allocation and fill times") ? c.Get(1, "defined flag") : std::nullopt;
            if (!defined || *defined == 0) {
                return c.error();
            }
            size = c.Get(4, "size");
            if (size && *size >= 0x80000000U) {  // INT32DECODE: a negative size copies nothing
                return std::nullopt;
            }
        } else {
            const std::optional<std::uint64_t> flags = c.Get(1, "flags");
            if (!flags || (*flags & ~kKnownFlags) != 0 || (*flags & kUndefinedValue) != 0 ||
                (*flags & kHaveValue) == 0) {
                return c.error();  // HDF5 rejects unknown flags; no value follows otherwise
            }
            size = c.Get(4, "size");
        }
    }
    if (size && *size > c.left()) {
        c.Fail("its fill value of " + std::to_string(*size) + " bytes does not fit the " +
               std::to_string(c.left()) + " bytes after its size");
    }
    return c.error();
}

// H5O__efl_decode: version 1, 3 reserved bytes, slots allocated (2), slots used (2), the local
// heap's address, then per used slot a name offset, a file offset and a size (lengths each).
// HDF5 writes the used slots into an array of the allocated ones (only asserting the order).
std::optional<std::string> CheckExternalFiles(const Resolved& m, const Superblock& sb) {
    Cursor c(m.bytes, "external file list message " + AtByte(m.at));
    const std::optional<std::uint64_t> version = c.Get(1, "version");
    if (!version || *version != 1 || !c.Skip(3, "reserved bytes")) {
        return c.error();  // HDF5: bad version number
    }
    const std::optional<std::uint64_t> allocated = c.Get(2, "allocated slots");
    const std::optional<std::uint64_t> used = allocated ? c.Get(2, "used slots") : std::nullopt;
    if (used && *used > *allocated) {
        c.Fail("it uses " + std::to_string(*used) + " slots of its " + std::to_string(*allocated) +
               " allocated");
    } else if (used && c.Skip(sb.offsets, "heap address")) {
        (void)c.Skip(*used * 3 * sb.lengths, "slots");
    }
    return c.error();
}

// The datatype (H5O_dtype_decode_helper, io/hdf5_datatype_check.hpp) and the dataspace
// (H5O__sdspace_decode; H5S_set_extent_simple's rule that a maximum is unlimited or at least
// its size; the dataset's bytes, elements times the datatype's size, within 64 bits).
std::optional<std::string> CheckType(const Resolved& m) {
    const std::string what = "datatype message " + AtByte(m.at);
    if (m.bytes.size() < kDatatypeHeaderBytes) {
        return what + ": its datatype of " + std::to_string(m.bytes.size()) +
               " bytes is shorter than a datatype's 8-byte header";
    }
    if (std::optional<std::string> why = CheckDatatypeEncoding(m.bytes.data(), m.bytes.size())) {
        return what + ": " + *why;
    }
    return std::nullopt;
}

std::optional<std::string> CheckSpace(const Resolved& m, LayoutContext& ctx) {
    const std::string what = "dataspace message " + AtByte(m.at);
    const std::optional<Extent> e = DecodeExtent(m.bytes.data(), m.bytes.size(), ctx.sb->lengths);
    if (!e) {
        return std::nullopt;  // HDF5 rejects the version or rank
    }
    if (e->need > m.bytes.size()) {
        return what + ": its dataspace needs " + std::to_string(e->need) +
               " bytes for its rank but has " + std::to_string(m.bytes.size());
    }
    for (std::size_t k = 0; k < e->maxima.size(); ++k) {
        if (e->maxima[k] != AllOnes(ctx.sb->lengths) && e->maxima[k] < e->sizes[k]) {
            return what + ": its maximum size " + std::to_string(e->maxima[k]) + " of dimension " +
                   std::to_string(k) + " is below its size " + std::to_string(e->sizes[k]);
        }
    }
    if (ctx.type_size && e->elements != 0 &&
        (e->elements == UINT64_MAX || *ctx.type_size > UINT64_MAX / e->elements)) {
        return what + ": its sizes times the datatype's " + std::to_string(*ctx.type_size) +
               " bytes exceed 64 bits";
    }
    ctx.extent = e;
    return std::nullopt;
}

}  // namespace

std::optional<std::string> FindCorruptDatasetMessages(std::uint64_t address,
                                                      std::uint64_t file_size,
                                                      const ReadAt& read) {
    const std::optional<Superblock> sb = ReadSuperblock(file_size, read);
    if (!sb) {
        return std::string(kNoSuperblockProblem);
    }
    const HeaderFile file{*sb, file_size, &read};
    std::map<std::uint16_t, Resolved> first;  // HDF5 decodes the first message of each type
    const std::optional<std::string> walked =
        WalkHeader(file, address, true, [&](const HeaderMessage& m) -> std::optional<std::string> {
            const bool decoded = m.type == kDatatypeMessage || m.type == kDataspaceMessage ||
                                 m.type == kLayoutMessage || m.type == kFilterPipelineMessage ||
                                 m.type == kFillValueMessage || m.type == kOldFillValueMessage ||
                                 m.type == kExternalFilesMessage;
            if (!decoded || first.count(m.type) != 0) {
                return std::nullopt;
            }
            Resolved r = ResolveMessage(file, m, MessageName(m.type) + " message " + AtByte(m.at));
            if (r.error) {
                return r.error;
            }
            first.emplace(m.type, std::move(r));
            return std::nullopt;
        });
    if (walked) {
        return walked;
    }
    const auto found = [&](std::uint16_t type) -> const Resolved* {
        const auto it = first.find(type);
        return it != first.end() && it->second.found ? &it->second : nullptr;
    };
    LayoutContext ctx;
    ctx.sb = &*sb;
    if (const Resolved* type = found(kDatatypeMessage)) {
        if (std::optional<std::string> why = CheckType(*type)) {
            return why;
        }
        ctx.type_size = DecodeLe(type->bytes.data() + 4, 4);
    }
    if (const Resolved* space = found(kDataspaceMessage)) {
        if (std::optional<std::string> why = CheckSpace(*space, ctx)) {
            return why;
        }
    }
    if (const Resolved* layout = found(kLayoutMessage)) {
        if (std::optional<std::string> why = CheckLayout(*layout, ctx)) {
            return why;
        }
    }
    if (const Resolved* pipeline = found(kFilterPipelineMessage)) {
        if (std::optional<std::string> why = CheckPipeline(*pipeline)) {
            return why;
        }
    }
    for (const std::uint16_t fill : {kFillValueMessage, kOldFillValueMessage}) {
        if (const Resolved* m = found(fill)) {
            if (std::optional<std::string> why = CheckFill(*m, fill)) {
                return why;
            }
        }
    }
    if (const Resolved* efl = found(kExternalFilesMessage)) {
        return CheckExternalFiles(*efl, *sb);
    }
    return std::nullopt;
}

}  // namespace casmap::io::h5
