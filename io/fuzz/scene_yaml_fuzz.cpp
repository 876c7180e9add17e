// libFuzzer target: arbitrary bytes as a scene YAML file through io::LoadScene (the reader the
// simulator commands use). Expected outcomes: a scene or an InputError; anything else (crash,
// other exception, sanitizer report, runaway allocation) is a finding.
#include <cstddef>
#include <cstdint>

#include "casmap/core/input_error.hpp"
#include "casmap/io/scene_file.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = casmap::fuzz::WriteInput(data, size, "scene.yaml");
    try {
        (void)casmap::io::LoadScene(path);
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
