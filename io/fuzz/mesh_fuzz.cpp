// libFuzzer target: arbitrary bytes as a mesh through io::ImportMeshFromMemory (assimp reading
// from memory, with the header checks ImportMesh makes). The first byte picks the format hint.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "casmap/core/input_error.hpp"
#include "casmap/io/mesh_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) {
        return 0;
    }
    static const char* const kHints[] = {"ply", "stl", "obj", "off"};
    const std::string hint = kHints[data[0] % 4];
    const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
    try {
        (void)casmap::io::ImportMeshFromMemory(bytes, hint, "fuzz." + hint,
                                               Eigen::Vector3d::Ones());
    } catch (const casmap::InputError&) {
        // a rejected mesh is an expected outcome
    }
    return 0;
}
