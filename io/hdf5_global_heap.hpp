#pragma once

// A check of an HDF5 file's global heap collections from the file's bytes, before HDF5 reads
// any of them (io/hdf5_util.cpp). HDF5 1.10.8 loops forever in H5HG_read (the collection
// decoder, H5HG__cache_heap_deserialize) when an object header in a collection has a size that
// makes the walk stand still or step backwards (fuzz finding, docs/fuzzing.md). Variable-length
// strings live in these collections, so casmap reads a variable-length string only from a file
// that passes this check. Run files of format version 2 hold no variable-length data at all.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace casmap::io::h5 {

/// Copies up to `size` bytes at `offset` of the file into `out`; returns how many it copied
/// (fewer only at the end of the file).
using ReadAt = std::function<std::size_t(std::uint64_t offset, std::size_t size, void* out)>;

/// The largest global heap collection casmap lets HDF5 read (64 MiB; docs/limits.md).
inline constexpr std::uint64_t kMaxGlobalHeapCollectionBytes = std::uint64_t{64} << 20;

/// Walks every global heap collection of the file the way HDF5 decodes it: each place whose
/// bytes start with the collection signature "GCOL" and version 1 (HDF5 rejects any other
/// version before decoding), with the superblock's size of lengths. Returns the reason the first
/// corrupt collection gives, or nullopt when every collection lies inside the file, is at least
/// HDF5's 4096-byte minimum and at most kMaxGlobalHeapCollectionBytes long, and its objects
/// each lie inside it, so HDF5's walk ends. A file whose superblock cannot be read at offset 0
/// (casmap and h5py write it there) is reported too.
[[nodiscard]] std::optional<std::string> FindCorruptGlobalHeap(std::uint64_t file_size,
                                                               const ReadAt& read);

}  // namespace casmap::io::h5
