// libFuzzer target: arbitrary bytes as an LMS 200 sensor YAML file through
// io::LoadLms200Config (the --sensor option's reader).
#include <cstddef>
#include <cstdint>

#include "casmap/core/input_error.hpp"
#include "casmap/io/sensor_config.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = casmap::fuzz::WriteInput(data, size, "sensor.yaml");
    try {
        (void)casmap::io::LoadLms200Config(path);
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
