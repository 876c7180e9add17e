#pragma once

// A check of an HDF5 datatype message's encoding, from the file's bytes, before HDF5 decodes it
// (io/hdf5_object_header.cpp runs it on every attribute's datatype). HDF5 1.10.8's decoder
// (H5O_dtype_decode_helper) reads each part without comparing it with the message's size:
// compound member and enum names with strdup, enum values and opaque tags with memcpy, and it
// writes an array's sizes into a 32-entry table whatever the rank the file gives.

#include <cstdint>
#include <optional>
#include <string>

namespace casmap::io::h5 {

/// The deepest nesting of datatypes (compound members, enum, variable-length and array bases)
/// casmap accepts; HDF5 decodes them recursively without a limit.
inline constexpr int kMaxDatatypeDepth = 32;

/// Decodes the datatype encoded in `size` bytes at `data` the way HDF5 1.10.8 does and returns
/// the rule the encoding breaks: a part (properties, member name, offset, dimensions, base
/// type, enum values, opaque tag) that runs past the `size` bytes, a name not NUL-terminated
/// within them, an array rank above 32, nesting deeper than kMaxDatatypeDepth. nullopt when
/// every byte HDF5 reads lies inside, or when HDF5 rejects the encoding before reading further
/// (a version other than 1-3, an unknown class, a size of 0, a compound without members).
[[nodiscard]] std::optional<std::string> CheckDatatypeEncoding(const std::uint8_t* data,
                                                               std::uint64_t size);

}  // namespace casmap::io::h5
