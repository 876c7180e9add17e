// libFuzzer target: arbitrary bytes as a TIFF map through io::ReadMapTiff (the reader of
// `filter --in`/`score` maps); accepted maps must match the size they report.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = casmap::fuzz::WriteInput(data, size, "map.tiff");
    try {
        const casmap::core::MapF map = casmap::io::ReadMapTiff(path);
        if (map.data.size() !=
            static_cast<std::size_t>(map.rows) * static_cast<std::size_t>(map.cols)) {
            std::abort();
        }
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
