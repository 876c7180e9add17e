#pragma once

// Shared by the io fuzz targets: the readers under test take a path (the code path the CLI
// uses), so each input is written to a per-process temporary file first.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace casmap::fuzz {

/// Writes `data` to <tmp>/casmap-fuzz-<pid>/<name> and returns that path.
inline std::string WriteInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("casmap-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path.string();
}

}  // namespace casmap::fuzz
