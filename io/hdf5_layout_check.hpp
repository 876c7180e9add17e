#pragma once

// The check of a dataset's layout message (io/hdf5_dataset_header.hpp), as HDF5 1.10.8's
// H5O__layout_decode reads it (it copies a compact layout's data with memcpy whatever the
// message's size) and as H5D__chunk_init and H5D__contig_check then use it.

#include <cstdint>
#include <optional>
#include <string>

#include "casmap/io/hdf5_header_walk.hpp"

namespace casmap::io::h5 {

/// What the dataset's other messages tell the layout check (nullopt: not known).
struct LayoutContext {
    const Superblock* sb = nullptr;
    std::optional<Extent> extent;            // a dataspace whose sizes fit its message
    std::optional<std::uint64_t> type_size;  // the datatype's size field
};

/// All bits of a `bytes`-byte field set (HDF5's undefined address, unlimited size).
[[nodiscard]] std::uint64_t AllOnes(std::size_t bytes);

/// "layout message at byte N: <rule>" for the layout message `m` (versions 1-4), nullopt when
/// sound or when HDF5 rejects it itself before reading past a field.
[[nodiscard]] std::optional<std::string> CheckLayout(const Resolved& m, const LayoutContext& ctx);

}  // namespace casmap::io::h5
