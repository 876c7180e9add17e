#pragma once

// A check of a chunked dataset's stored chunks before H5Dread (io/hdf5_file_reader.cpp). HDF5
// 1.10.8 runs a chunk's bytes through the reverse of its filter pipeline and then copies a whole
// chunk (its dimensions times the element size) out of whatever the filters returned, without
// comparing the sizes (older releases did: "data pipeline read failed"). A deflate stream that
// inflates to fewer bytes than its chunk holds, or an unfiltered chunk stored with another size,
// makes it read past its buffer (found while checking the fuzz findings of session 10: a chunk
// of 6 x 46 336 floats whose dataspace may grow, with 4 344 bytes stored).

#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <string>

namespace casmap::io::h5 {

/// The largest chunk (its dimensions times the element size) casmap reads: HDF5 allocates a
/// whole chunk per chunk it reads. casmap writes 256 KiB chunks, h5py's automatic ones are at
/// most 1 MiB.
inline constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{64} << 20;

/// How FindBadChunk's reason starts when the dataset uses a filter casmap does not read (not a
/// sign of corruption).
inline constexpr const char* kUnsupportedFilter = "its filter ";

/// For a chunked dataset `dataset` (anything else passes): every stored chunk, read raw with
/// H5Dread_chunk and run through the reverse of the filters it went through (Fletcher-32:
/// 4 bytes of checksum dropped; deflate: inflated; shuffle: same size), must come out exactly
/// the chunk's size, and no stored chunk may be longer than the file (`file_size`) or than any
/// encoding of its bytes. Returns the rule the first chunk breaks, a chunk above kMaxChunkBytes,
/// a filter other than those three ("not one casmap reads"), or nullopt. It inflates every chunk
/// once more than H5Dread does (counting the bytes, not keeping them).
[[nodiscard]] std::optional<std::string> FindBadChunk(hid_t dataset, std::uint64_t file_size);

}  // namespace casmap::io::h5
