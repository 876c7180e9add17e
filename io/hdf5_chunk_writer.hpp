#pragma once

// Chunks of whole rows written through the dataset's filter pipeline done here: HDF5's byte
// shuffle (optional, chosen per dataset) and a zlib stream, stored with H5Dwrite_chunk. Every
// HDF5 reader decodes them like its own chunks. The partial last chunk is padded with zeros
// (readers ignore what lies outside the dataset). Used by WriteDataset (io/hdf5_util.cpp).
//
// The encoder is chosen per dataset on its first chunk, deterministically (by sizes, never by
// time): casmap's DeflateZlib (deflate_stream.hpp) keeps arrays that compress at least
// kOwnMinRatio (labels, status, smooth poses and true ranges: 3-5x faster than libdeflate
// there, and smaller) or come within 2 % of libdeflate's size; other noisy arrays (measured
// ranges, moving orientations) go to libdeflate level 1 (when built with it), byte-shuffled
// or not, whichever is smaller.

#include <hdf5.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "casmap/io/hdf5_util.hpp"

#if defined(CASMAP_HAVE_LIBDEFLATE)
struct libdeflate_compressor;
#endif

namespace casmap::io::h5 {

/// Writes one chunked dataset's rows (from `data`, or from `fill` when `data` is null), all
/// sizes in elements of `element` bytes; `dims` and `chunk` as given to HDF5.
class ChunkWriter {
public:
    ChunkWriter(const std::vector<hsize_t>& dims,
                const std::vector<hsize_t>& chunk,
                std::size_t element,
                const void* data,
                const RowFill* fill);

    /// Picks the encoder and the shuffle on the first chunk and keeps that chunk's stream.
    /// Returns whether the dataset's pipeline has the shuffle filter.
    bool Choose();

    /// Writes every chunk into `dataset` (of rank `rank`) with H5Dwrite_chunk.
    void Write(hid_t dataset, std::size_t rank);

private:
    static constexpr std::size_t kOwnMinRatio = 4;
    static constexpr std::size_t kOwnMaxExcessPercent = 102;

    // The zlib stream of the chunk starting at `row`, with the current choices.
    void Encode(std::size_t row, std::vector<unsigned char>& out);

    std::size_t element_;
    std::size_t rows_;
    std::size_t chunk_rows_;
    std::size_t row_elements_ = 1;
    std::size_t chunk_elements_ = 0;
    const unsigned char* data_;
    const RowFill* fill_;
    bool shuffle_ = false;
#if defined(CASMAP_HAVE_LIBDEFLATE)
    struct FreeCompressor {
        void operator()(libdeflate_compressor* c) const;
    };
    std::unique_ptr<libdeflate_compressor, FreeCompressor> compressor_;
#endif
    std::vector<unsigned char> plain_;
    std::vector<unsigned char> shuffled_;
    std::vector<unsigned char> first_;
    std::vector<unsigned char> stream_;
};

}  // namespace casmap::io::h5
