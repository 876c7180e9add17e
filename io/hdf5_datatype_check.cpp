#include "casmap/io/hdf5_datatype_check.hpp"

#include <cstring>

namespace casmap::io::h5 {
namespace {

// Datatype classes (HDF5 file format specification, datatype message).
enum Class : std::uint8_t {
    kFixedPoint = 0,
    kFloatingPoint = 1,
    kTime = 2,
    kString = 3,
    kBitfield = 4,
    kOpaque = 5,
    kCompound = 6,
    kReference = 7,
    kEnumerated = 8,
    kVariableLength = 9,
    kArray = 10,
};

constexpr std::uint8_t kMaxArrayRank = 32;         // H5S_MAX_RANK, the size of HDF5's table
constexpr std::uint8_t kMaxMemberArrayRank = 4;    // compound members of version 1
constexpr std::uint64_t kV1MemberExtraBytes = 28;  // rank 1, reserved 3 + 4 + 4, sizes 4 x 4

std::uint64_t Decode(const std::uint8_t* p, std::size_t bytes) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
        value |= static_cast<std::uint64_t>(p[i]) << (8U * i);
    }
    return value;
}

// The bytes version 3 uses for a member offset: the fewest that hold the compound's size
// (H5VM_limit_enc_size: floor(log2(size)) / 8 + 1).
std::size_t OffsetBytes(std::uint64_t size) {
    std::size_t log2 = 0;
    while (size >>= 1U) {
        ++log2;
    }
    return log2 / 8 + 1;
}

class Decoder {
public:
    Decoder(const std::uint8_t* data, std::uint64_t size) : data_(data), size_(size) {}

    // false when the encoding breaks a rule (error() says which) or HDF5 stops reading it.
    bool Type(int depth, std::uint64_t* type_size);
    [[nodiscard]] const std::optional<std::string>& error() const { return error_; }

private:
    bool Fail(const std::string& why) {
        error_ = why + " (its datatype's " + std::to_string(size_) + " bytes)";
        return false;
    }
    bool Take(std::uint64_t bytes, const std::string& part) {
        if (size_ - pos_ < bytes) {
            return Fail("datatype " + part + " at byte " + std::to_string(pos_) +
                        " runs past the end");
        }
        pos_ += bytes;
        return true;
    }
    // A name and its NUL, padded to 8 bytes before version 3.
    bool Name(unsigned version, const std::string& part) {
        const void* nul = std::memchr(data_ + pos_, '\0', static_cast<std::size_t>(size_ - pos_));
        if (nul == nullptr) {
            return Fail("datatype " + part + " at byte " + std::to_string(pos_) +
                        " is not NUL-terminated");
        }
        const auto length =
            static_cast<std::uint64_t>(static_cast<const std::uint8_t*>(nul) - (data_ + pos_));
        return Take(version >= 3 ? length + 1 : (length + 8) / 8 * 8, part);
    }
    bool Compound(unsigned version, std::uint32_t flags, std::uint64_t size, int depth);
    bool Enumerated(unsigned version, std::uint32_t flags, int depth);
    bool Array(unsigned version, int depth);

    const std::uint8_t* data_;
    std::uint64_t size_;
    std::uint64_t pos_ = 0;
    std::optional<std::string> error_;
};

bool Decoder::Type(int depth, std::uint64_t* type_size) {
    if (depth > kMaxDatatypeDepth) {
        return Fail("datatypes nested deeper than " + std::to_string(kMaxDatatypeDepth));
    }
    const std::uint64_t start = pos_;
    if (!Take(8, "header")) {
        return false;
    }
    const unsigned version = data_[start] >> 4U;
    const unsigned type_class = data_[start] & 0x0FU;
    const auto flags = static_cast<std::uint32_t>(Decode(data_ + start + 1, 3));
    *type_size = Decode(data_ + start + 4, 4);
    if (version < 1 || version > 3 || *type_size == 0) {
        return false;  // HDF5 rejects it here
    }
    std::uint64_t base = 0;
    switch (type_class) {
        case kFixedPoint:
        case kBitfield:
            return Take(4, "properties");
        case kFloatingPoint:
            return Take(12, "properties");
        case kTime:
            return Take(2, "properties");
        case kString:
        case kReference:
            return true;
        case kOpaque:
            return Take(flags & 0xFFU, "opaque tag");
        case kCompound:
            return Compound(version, flags, *type_size, depth);
        case kEnumerated:
            return Enumerated(version, flags, depth);
        case kVariableLength:
            return Type(depth + 1, &base);
        case kArray:
            return Array(version, depth);
        default:
            return false;  // HDF5: unknown datatype class
    }
}

// Members: name, offset (4 bytes; version 3: OffsetBytes), version 1 an array rank (at most
// 4), reserved bytes and 4 sizes, then the member's datatype.
bool Decoder::Compound(unsigned version, std::uint32_t flags, std::uint64_t size, int depth) {
    const std::uint32_t members = flags & 0xFFFFU;
    if (members == 0) {
        return false;  // HDF5: invalid number of members
    }
    for (std::uint32_t i = 0; i < members; ++i) {
        const std::string part = "compound member " + std::to_string(i);
        if (!Name(version, part + " name") ||
            !Take(version >= 3 ? OffsetBytes(size) : 4, part + " offset")) {
            return false;
        }
        if (version == 1) {
            if (size_ - pos_ >= 1 && data_[pos_] > kMaxMemberArrayRank) {
                return false;  // HDF5: invalid number of dimensions
            }
            if (!Take(kV1MemberExtraBytes, part + " dimensions")) {
                return false;
            }
        }
        std::uint64_t member = 0;
        if (!Type(depth + 1, &member)) {
            return false;
        }
    }
    return true;
}

// The base type, the member names, then one base-type value per member.
bool Decoder::Enumerated(unsigned version, std::uint32_t flags, int depth) {
    const std::uint32_t members = flags & 0xFFFFU;
    std::uint64_t base = 0;
    if (!Type(depth + 1, &base)) {
        return false;
    }
    for (std::uint32_t i = 0; i < members; ++i) {
        if (!Name(version, "enum member " + std::to_string(i) + " name")) {
            return false;
        }
    }
    if (base > (size_ - pos_) / (members == 0 ? 1 : members)) {
        return Fail("datatype enum values (" + std::to_string(members) + " of " +
                    std::to_string(base) + " bytes) at byte " + std::to_string(pos_) +
                    " run past the end");
    }
    return Take(base * members, "enum values");
}

// The rank (before version 3 followed by 3 reserved bytes), 4 bytes per size, before version 3
// 4 bytes of permutation per dimension, then the base type.
bool Decoder::Array(unsigned version, int depth) {
    if (!Take(1, "array rank")) {
        return false;
    }
    const std::uint8_t rank = data_[pos_ - 1];
    if (rank > kMaxArrayRank) {
        return Fail("datatype array rank " + std::to_string(rank) + " at byte " +
                    std::to_string(pos_ - 1) + " is above " + std::to_string(kMaxArrayRank));
    }
    const std::uint64_t sizes = std::uint64_t{4} * rank * (version < 3 ? 2 : 1);
    std::uint64_t base = 0;
    return Take(version < 3 ? 3 : 0, "array reserved bytes") && Take(sizes, "array sizes") &&
           Type(depth + 1, &base);
}

}  // namespace

std::optional<std::string> CheckDatatypeEncoding(const std::uint8_t* data, std::uint64_t size) {
    Decoder decoder(data, size);
    std::uint64_t type_size = 0;
    (void)decoder.Type(0, &type_size);
    return decoder.error();
}

}  // namespace casmap::io::h5
