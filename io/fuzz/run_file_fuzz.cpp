// libFuzzer target: arbitrary bytes as a run file through io::ReadRunFileImage (the HDF5 core
// driver opens the bytes as a file image; the validation is ReadRunFile's).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "casmap/core/input_error.hpp"
#include "casmap/io/run_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)casmap::io::ReadRunFileImage(bytes, "fuzz.h5");
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
