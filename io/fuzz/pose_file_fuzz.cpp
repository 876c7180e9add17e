// libFuzzer target: arbitrary bytes as a pose file through drivers::ReadPoseFile (the reader
// of `record --poses` and `map --poses`); accepted files must write back and re-read to the
// same number of poses.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = casmap::fuzz::WriteInput(data, size, "poses.txt");
    try {
        const casmap::core::Trajectory poses = casmap::drivers::ReadPoseFile(path);
        std::istringstream again(casmap::drivers::PoseFileText(poses));
        if (casmap::drivers::ReadPoses(again, "rewritten").size() != poses.size()) {
            std::abort();
        }
    } catch (const casmap::InputError&) {
        // a rejected file is an expected outcome
    }
    return 0;
}
