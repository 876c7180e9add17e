#include "casmap/io/hdf5_chunk_check.hpp"

#include <zlib.h>
#if CASMAP_HAVE_LIBDEFLATE
#include <libdeflate.h>

#include <memory>
#endif

#include <array>
#include <cstdint>
#include <vector>

#include "casmap/io/hdf5_util.hpp"  // Id

namespace casmap::io::h5 {
namespace {

constexpr int kMaxRank = 32;  // H5S_MAX_RANK

std::string OffsetText(const std::vector<hsize_t>& offset) {
    std::string text = "(";
    for (std::size_t k = 0; k < offset.size(); ++k) {
        text += (k == 0 ? "" : ", ") + std::to_string(offset[k]);
    }
    return text + ")";
}

#if CASMAP_HAVE_LIBDEFLATE
// The same with libdeflate (about 2.5 times zlib's speed) into `out`, a chunk's bytes (kept
// between chunks); nullopt when the stream is not whole or inflates to more (zlib then counts,
// up to the Fletcher-32 sizes a pipeline allows, and says which). The decompressor is shared:
// every HDF5 read runs under LibraryLock.
std::optional<std::uint64_t> InflatedSizeFast(const std::vector<std::uint8_t>& in,
                                              std::uint64_t chunk_bytes,
                                              std::vector<std::uint8_t>& out) {
    struct Free {
        void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
    };
    static const std::unique_ptr<libdeflate_decompressor, Free> decompressor(
        libdeflate_alloc_decompressor());
    out.resize(static_cast<std::size_t>(chunk_bytes));
    std::size_t produced = 0;
    if (decompressor == nullptr ||
        libdeflate_zlib_decompress(decompressor.get(), in.data(), in.size(), out.data(), out.size(),
                                   &produced) != LIBDEFLATE_SUCCESS) {
        return std::nullopt;  // not a whole stream, or more bytes than the chunk: zlib says
    }
    return produced;
}
#endif

// The bytes the zlib stream `in` inflates to (H5Z__filter_deflate's reverse direction: inflate
// until the stream ends), counted in a small buffer; nullopt when it is not a whole stream or
// inflates to more than `limit` bytes.
std::optional<std::uint64_t> InflatedSize(const std::vector<std::uint8_t>& in,
                                          std::uint64_t limit) {
    std::array<std::uint8_t, 1U << 16> out{};
    z_stream z{};
    if (inflateInit(&z) != Z_OK) {
        return std::nullopt;
    }
    z.next_in = const_cast<Bytef*>(in.data());
    z.avail_in = static_cast<uInt>(in.size());
    int status = Z_OK;
    while (status == Z_OK && z.total_out <= limit) {
        z.next_out = out.data();
        z.avail_out = static_cast<uInt>(out.size());
        status = inflate(&z, Z_NO_FLUSH);
    }
    const std::uint64_t produced = z.total_out;
    inflateEnd(&z);
    if (status != Z_STREAM_END || produced > limit) {
        return std::nullopt;
    }
    return produced;
}

}  // namespace

std::optional<std::string> FindBadChunk(hid_t dataset, std::uint64_t file_size) {
    const Id dcpl(H5Dget_create_plist(dataset), H5Pclose);
    if (dcpl.get() < 0 || H5Pget_layout(dcpl.get()) != H5D_CHUNKED) {
        return std::nullopt;
    }
    std::array<hsize_t, kMaxRank> dims{};
    const int rank = H5Pget_chunk(dcpl.get(), kMaxRank, dims.data());
    const Id type(H5Dget_type(dataset), H5Tclose);
    if (rank <= 0 || type.get() < 0) {
        return "its chunk dimensions cannot be read";
    }
    std::uint64_t chunk_bytes = H5Tget_size(type.get());
    for (int k = 0; k < rank; ++k) {  // none is 0 (the layout check)
        if (dims[k] != 0 && chunk_bytes > kMaxChunkBytes / dims[k]) {
            return "its chunk is larger than casmap's limit of " + std::to_string(kMaxChunkBytes) +
                   " bytes, see docs/limits.md";
        }
        chunk_bytes *= dims[k];
    }
    std::vector<H5Z_filter_t> filters;
    const int count = H5Pget_nfilters(dcpl.get());
    for (int i = 0; i < count; ++i) {
        unsigned flags = 0;
        std::size_t values = 0;
        unsigned config = 0;
        const H5Z_filter_t id = H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags,
                                               &values, nullptr, 0, nullptr, &config);
        if (id != H5Z_FILTER_DEFLATE && id != H5Z_FILTER_SHUFFLE && id != H5Z_FILTER_FLETCHER32) {
            return std::string(kUnsupportedFilter) + std::to_string(id) +
                   " is not one casmap reads (deflate, shuffle, Fletcher-32)";
        }
        filters.push_back(id);
    }
    const Id space(H5Dget_space(dataset), H5Sclose);
    hsize_t chunks = 0;
    if (space.get() < 0 || H5Dget_num_chunks(dataset, space.get(), &chunks) < 0) {
        return "its chunk index cannot be read";
    }
    // A stored chunk is at most its size plus deflate's worst-case growth and checksums.
    const std::uint64_t max_stored = chunk_bytes + chunk_bytes / 8 + 1024;
    std::vector<hsize_t> offset(static_cast<std::size_t>(rank));
    std::vector<std::uint8_t> raw;
#if CASMAP_HAVE_LIBDEFLATE
    std::vector<std::uint8_t> scratch;  // libdeflate's output
#endif
    for (hsize_t c = 0; c < chunks; ++c) {
        unsigned mask = 0;
        haddr_t address = 0;
        hsize_t stored = 0;
        if (H5Dget_chunk_info(dataset, space.get(), c, offset.data(), &mask, &address, &stored) <
            0) {
            return "its chunk " + std::to_string(c) + " cannot be found";
        }
        const std::string what = "its chunk at " + OffsetText(offset);
        if (stored > max_stored || stored > file_size) {
            return what + " stores " + std::to_string(stored) + " bytes for " +
                   std::to_string(chunk_bytes);
        }
        raw.resize(static_cast<std::size_t>(stored));
        std::uint32_t read_mask = 0;
        if (H5Dread_chunk(dataset, H5P_DEFAULT, offset.data(), &read_mask, raw.data()) < 0) {
            return what + " cannot be read";
        }
        std::size_t size = raw.size();
        for (std::size_t i = filters.size(); i-- > 0;) {  // the reverse of the pipeline
            if ((mask & (1U << i)) != 0) {
                continue;  // the writer skipped this filter for this chunk
            }
            if (filters[i] == H5Z_FILTER_FLETCHER32) {
                if (size < 4) {
                    return what + " is shorter than its 4-byte Fletcher-32 checksum";
                }
                size -= 4;
            } else if (filters[i] == H5Z_FILTER_DEFLATE) {
                raw.resize(size);
                std::optional<std::uint64_t> inflated;
#if CASMAP_HAVE_LIBDEFLATE
                inflated = InflatedSizeFast(raw, chunk_bytes, scratch);
#endif
                if (!inflated) {
                    inflated = InflatedSize(raw, chunk_bytes + 64);
                }
                if (!inflated) {
                    return what + " is not a deflate stream of at most " +
                           std::to_string(chunk_bytes + 64) + " bytes";
                }
                size = static_cast<std::size_t>(*inflated);
            }
        }
        if (size != chunk_bytes) {
            return what + " holds " + std::to_string(size) + " bytes after its filters, not the " +
                   std::to_string(chunk_bytes) + " of its dimensions";
        }
    }
    return std::nullopt;
}

}  // namespace casmap::io::h5
