#pragma once

// A check of a dataset's own object header messages, from the file's bytes, before HDF5 decodes
// them in H5Dopen2 (io/hdf5_file_reader.cpp). HDF5 1.10.8's decoders read what the message's
// fields say without comparing it with the message's size: a compact layout's data and a fill
// value are copied with memcpy (H5O__layout_decode, H5O_fill_new_decode), a filter's name with
// strlen/strncpy (H5O__pline_decode), an external file list's slots are written into an array
// sized by another field (H5O__efl_decode), a datatype as io/hdf5_datatype_check.hpp says.
// Like the attribute check (io/hdf5_object_header.hpp), headers of both versions are walked: a
// version 2 header's checksum stops random corruption, not a crafted file.

#include <cstdint>
#include <optional>
#include <string>

#include "casmap/io/hdf5_global_heap.hpp"  // ReadAt

namespace casmap::io::h5 {

/// Walks the dataset object header at `address` (as H5Oget_info reports it; the superblock at
/// byte 0) and checks the first message of each type H5Dopen2 decodes, as HDF5 1.10.8 decodes
/// it (shared messages read where their reference points):
/// - datatype: at least its 8-byte header, and an encoding CheckDatatypeEncoding accepts;
/// - dataspace: its sizes (and maxima) fit the message for its rank; each maximum is at least
///   its size or unlimited; sizes times the datatype's size fit 64 bits;
/// - layout: every field its version and class have lies inside the message; a layout class
///   of 0-2 (versions 1-2); a compact layout's data fits the message; a chunk has the
///   dataspace's rank + 1 dimensions, none 0; contiguous data (address and size) ends within
///   the superblock's end-of-file address;
/// - filter pipeline: each filter's name lies inside the message and is NUL-terminated there,
///   and so do its client data values;
/// - fill value (new and old): the value fits the message;
/// - external file list: its used slots are no more than its allocated ones and lie inside
///   the message.
/// Returns "<message> message at byte <offset>: <rule broken>" for the first bad message (or
/// the walk's reason for a bad header block), nullopt when all are sound, the header is of a
/// version HDF5 rejects, or HDF5 rejects a field itself before reading past it (a version or rank
/// it does not know). A superblock that cannot be read at byte 0 is reported.
[[nodiscard]] std::optional<std::string> FindCorruptDatasetMessages(std::uint64_t address,
                                                                    std::uint64_t file_size,
                                                                    const ReadAt& read);

}  // namespace casmap::io::h5
