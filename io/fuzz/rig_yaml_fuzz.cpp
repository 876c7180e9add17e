// libFuzzer target: arbitrary bytes as a rig YAML file through io::LoadRigConfig (the --rig
// option's reader), then the effective-config writer on what was accepted.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "casmap/core/input_error.hpp"
#include "casmap/io/rig_config.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = casmap::fuzz::WriteInput(data, size, "rig.yaml");
    try {
        const casmap::io::RigConfig config = casmap::io::LoadRigConfig(path);
        (void)casmap::io::RigConfigToYaml(config);
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
