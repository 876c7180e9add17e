#include "casmap/io/hdf5_chunk_writer.hpp"

#if defined(CASMAP_HAVE_LIBDEFLATE)
#include <libdeflate.h>
#endif

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "casmap/io/deflate_stream.hpp"

namespace casmap::io::h5 {
namespace {

// H5Z shuffle: byte b of element i goes to b * count + i. The common sizes have their own
// loops (the compiler vectorises them; ~6x faster than the general one).
template <std::size_t kElement>
void ShuffleFixed(const unsigned char* __restrict in,
                  std::size_t count,
                  unsigned char* __restrict out) {
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t b = 0; b < kElement; ++b) {
            out[b * count + i] = in[i * kElement + b];
        }
    }
}

void Shuffle(const unsigned char* in, std::size_t element, std::size_t count, unsigned char* out) {
    switch (element) {
        case 2:
            ShuffleFixed<2>(in, count, out);
            return;
        case 4:
            ShuffleFixed<4>(in, count, out);
            return;
        case 8:
            ShuffleFixed<8>(in, count, out);
            return;
        default:
            for (std::size_t b = 0; b < element; ++b) {
                for (std::size_t i = 0; i < count; ++i) {
                    out[b * count + i] = in[i * element + b];
                }
            }
    }
}

}  // namespace

ChunkWriter::ChunkWriter(const std::vector<hsize_t>& dims,
                         const std::vector<hsize_t>& chunk,
                         std::size_t element,
                         const void* data,
                         const RowFill* fill)
    : element_(element),
      rows_(static_cast<std::size_t>(dims[0])),
      chunk_rows_(static_cast<std::size_t>(chunk[0])),
      data_(static_cast<const unsigned char*>(data)),
      fill_(fill) {
    for (std::size_t k = 1; k < dims.size(); ++k) {
        row_elements_ *= static_cast<std::size_t>(dims[k]);
    }
    chunk_elements_ = chunk_rows_ * row_elements_;
    plain_.resize(chunk_elements_ * element_);
    shuffled_.resize(chunk_elements_ * element_);
}
bool ChunkWriter::Choose() {
    shuffle_ = element_ > 1;
    Encode(0, first_);
#if defined(CASMAP_HAVE_LIBDEFLATE)
    if (first_.size() * kOwnMinRatio > chunk_elements_ * element_) {
        compressor_.reset(libdeflate_alloc_compressor(1));
        if (!compressor_) {
            throw std::runtime_error("libdeflate: cannot allocate a compressor");
        }
        std::vector<unsigned char> own;
        own.swap(first_);
        const bool own_shuffle = shuffle_;
        Encode(0, first_);
        if (element_ > 1) {
            std::vector<unsigned char> plain_stream;
            shuffle_ = false;
            Encode(0, plain_stream);
            shuffle_ = plain_stream.size() >= first_.size();
            if (!shuffle_) {
                first_.swap(plain_stream);
            }
        }
        // Within 2 % of libdeflate's size (raw values, a table run's positions) casmap's
        // encoder is still the faster one.
        if (own.size() * 100 <= first_.size() * kOwnMaxExcessPercent) {
            compressor_.reset();
            shuffle_ = own_shuffle;
            first_.swap(own);
        }
    }
#endif
    return shuffle_;
}
void ChunkWriter::Write(hid_t dataset, std::size_t rank) {
    std::vector<hsize_t> offset(rank, 0);
    for (std::size_t row = 0; row < rows_; row += chunk_rows_) {
        if (row > 0) {
            Encode(row, stream_);
        } else {
            stream_.swap(first_);
        }
        offset[0] = row;
        Check(
            H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, offset.data(), stream_.size(), stream_.data()),
            "H5Dwrite_chunk");
    }
}
void ChunkWriter::Encode(std::size_t row, std::vector<unsigned char>& out) {
    const std::size_t chunk_bytes = chunk_elements_ * element_;
    const std::size_t used = std::min(chunk_rows_, rows_ - row) * row_elements_ * element_;
    const unsigned char* in = nullptr;
    if (fill_ != nullptr) {  // the rows straight into the chunk buffer
        (*fill_)(row, std::min(chunk_rows_, rows_ - row), plain_.data());
        std::fill(plain_.begin() + static_cast<std::ptrdiff_t>(used), plain_.end(), 0);
        in = plain_.data();
    } else {
        in = data_ + row * row_elements_ * element_;
        if (used < chunk_bytes) {
            std::memcpy(plain_.data(), in, used);
            std::fill(plain_.begin() + static_cast<std::ptrdiff_t>(used), plain_.end(), 0);
            in = plain_.data();
        }
    }
    DeflateLayout layout;
    if (shuffle_) {
        Shuffle(in, element_, chunk_elements_, shuffled_.data());
        in = shuffled_.data();
        // One segment per byte plane; repeats of the previous byte or row in the plane.
        layout.segment_bytes = chunk_elements_;
        layout.distance_a = 1;
        layout.distance_b = row_elements_ > 1 ? row_elements_ : 0;
    } else {  // repeats of the previous element or row
        layout.distance_a = element_;
        layout.distance_b = row_elements_ > 1 ? row_elements_ * element_ : 0;
    }
#if defined(CASMAP_HAVE_LIBDEFLATE)
    if (compressor_) {
        out.resize(libdeflate_zlib_compress_bound(compressor_.get(), chunk_bytes));
        const std::size_t size =
            libdeflate_zlib_compress(compressor_.get(), in, chunk_bytes, out.data(), out.size());
        if (size == 0) {
            throw std::runtime_error("libdeflate: compression failed");
        }
        out.resize(size);
        return;
    }
#endif
    DeflateZlib({in, chunk_bytes}, layout, out);
}
#if defined(CASMAP_HAVE_LIBDEFLATE)
void ChunkWriter::FreeCompressor::operator()(libdeflate_compressor* c) const {
    libdeflate_free_compressor(c);
}
#endif

}  // namespace casmap::io::h5
