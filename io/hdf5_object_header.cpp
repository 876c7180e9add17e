#include "casmap/io/hdf5_object_header.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "casmap/io/hdf5_datatype_check.hpp"
#include "casmap/io/hdf5_header_walk.hpp"

namespace casmap::io::h5 {
namespace {

std::uint64_t Align8(std::uint64_t n) { return (n + 7) / 8 * 8; }

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
    std::uint64_t element = DecodeLe(parts.datatype.data() + 4, 4);
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

// An attribute message (versions 1-3) as H5O_attr_decode reads it: version, flags (versions
// 2-3: datatype (1) and dataspace (2) shared), the sizes of name (NUL included), datatype and
// dataspace, [encoding, version 3], then the three parts, each padded to 8 bytes in version 1,
// then the value.
std::optional<std::string> CheckAttribute(const HeaderFile& file, const HeaderMessage& m) {
    const std::uint8_t* data = m.data;
    const std::string what = "attribute message " + AtByte(m.at);
    if (m.size < 8) {
        return what + " is shorter than its 8-byte header";
    }
    const std::uint8_t version = data[0];
    if (version < 1 || version > 3) {
        return std::nullopt;  // HDF5 rejects the version before it reads a name
    }
    const std::uint64_t name = DecodeLe(data + 2, 2);
    const std::uint64_t datatype = DecodeLe(data + 4, 2);
    const std::uint64_t dataspace = DecodeLe(data + 6, 2);
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
        ResolveMessage(file,
                       {kDatatypeMessage, (shared & 1U) != 0 ? kMessageShared : std::uint8_t{0},
                        type, datatype, m.at},
                       what);
    const Resolved s =
        ResolveMessage(file,
                       {kDataspaceMessage, (shared & 2U) != 0 ? kMessageShared : std::uint8_t{0},
                        type + pad(datatype), dataspace, m.at},
                       what);
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
        return std::string(kNoSuperblockProblem);
    }
    const HeaderFile file{*sb, file_size, &read};
    return WalkHeader(file, address, true,
                      [&](const HeaderMessage& m) -> std::optional<std::string> {
                          if (m.type == kAttributeMessage && (m.flags & kMessageShared) == 0) {
                              return CheckAttribute(file, m);
                          }
                          return std::nullopt;
                      });
}

}  // namespace casmap::io::h5
