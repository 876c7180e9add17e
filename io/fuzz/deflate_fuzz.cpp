// libFuzzer target: casmap's own zlib encoder (io/deflate_stream.hpp, the run-file writer's)
// on arbitrary bytes and layouts. The first 7 bytes choose the layout (segment size, the two
// match distances, the hash table); the rest is the input. Every stream must inflate with
// zlib to exactly the input, and encoding twice must give the same bytes; ASan catches a write
// past the output the encoder sized for itself.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

#include "casmap/io/deflate_stream.hpp"

namespace {

std::size_t Read16(const std::uint8_t* p) {
    return static_cast<std::size_t>(p[0]) | (static_cast<std::size_t>(p[1]) << 8);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    constexpr std::size_t kHeader = 7;
    if (size < kHeader) {
        return 0;
    }
    casmap::io::h5::DeflateLayout layout;
    layout.segment_bytes = Read16(data);           // 0 = the default 65535-byte segments
    layout.distance_a = Read16(data + 2) % 32769;  // 0 .. 32768 (0 = not used)
    layout.distance_b = Read16(data + 4) % 32769;
    layout.hashed = (data[6] & 1) != 0;
    const std::span<const unsigned char> in(data + kHeader, size - kHeader);

    std::vector<unsigned char> stream;
    casmap::io::h5::DeflateZlib(in, layout, stream);

    std::vector<unsigned char> out(in.size() + 1);  // a stream that decodes to more would show
    uLongf got = out.size();
    if (uncompress(out.data(), &got, stream.data(), stream.size()) != Z_OK || got != in.size() ||
        (got != 0 && std::memcmp(out.data(), in.data(), got) != 0)) {
        std::abort();
    }
    std::vector<unsigned char> again;
    casmap::io::h5::DeflateZlib(in, layout, again);
    if (again != stream) {
        std::abort();
    }
    return 0;
}
