#pragma once

// A check of the attribute messages in an HDF5 object header, from the file's bytes, before
// HDF5 decodes them (io/hdf5_util.cpp). HDF5 1.10.8 copies an attribute's name with strdup
// (H5O_attr_decode) without checking that a NUL ends it inside the message, so a header whose
// name runs on reads past the end of HDF5's buffer, and copies the attribute's value (datatype
// size times the dataspace's elements) without comparing its size with the message's (fuzz
// findings, docs/fuzzing.md). Headers of both versions are walked: a version 2 header's
// checksum stops random corruption, not a crafted file. Attributes a version 2 header stores
// densely (in a fractal heap, h5py's latest format past 8 attributes) are not checked.

#include <cstdint>
#include <optional>
#include <string>

#include "casmap/io/hdf5_global_heap.hpp"  // ReadAt
#include "casmap/io/hdf5_header_walk.hpp"  // kMaxHeaderContinuations

namespace casmap::io::h5 {

/// Walks the object header at `address` (from the superblock, which must be at byte 0; as
/// H5Oget_info reports it) the way HDF5 lays it out: the first chunk and each continuation
/// block. Returns the reason the first bad attribute message or block gives (its name is not
/// NUL-terminated inside the message; name, datatype and dataspace do not fit the message; the
/// dataspace is shorter than its rank needs or the datatype than its 8-byte header; the value
/// does not fit the bytes after the dataspace; a block outside the file; more than
/// kMaxHeaderContinuations blocks), or nullopt when every attribute message is sound. A shared
/// (committed) datatype or dataspace is read where the reference points (an object header of
/// either version), as HDF5 reads it; one in the shared message heap is not checked. A header
/// of a version HDF5 rejects itself is accepted as it is; a superblock that cannot be read at
/// byte 0 is reported.
[[nodiscard]] std::optional<std::string> FindCorruptAttributeMessages(std::uint64_t address,
                                                                      std::uint64_t file_size,
                                                                      const ReadAt& read);

}  // namespace casmap::io::h5
