// The run file's public entry points (run_file.hpp): atomic writes, reads that turn a corrupt
// HDF5 structure into an InputError, and adding map layers. The layout itself is written by
// run_file_write.cpp and read by run_file_read.cpp (run_file_detail.hpp).
#include "casmap/io/run_file.hpp"

#include <stdexcept>
#include <string>
#include <string_view>

#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file_detail.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;

// A file whose HDF5 structure is corrupt makes the HDF5 helpers throw std::runtime_error; to a
// caller that is bad input, named by the file (found by io/fuzz/run_file_fuzz).
template <typename Read>
RunData ReadAsInput(const std::string& name, const Read& read) {
    try {
        return read();
    } catch (const InputError&) {
        throw;
    } catch (const std::runtime_error& e) {
        throw MakeInputError(name, "file", "",
                             std::string("unreadable HDF5 run file: ") + e.what());
    }
}

}  // namespace

void WriteRunFile(const fs::path& path, const RunData& data) {
    WriteAtomically(path, [&](const fs::path& tmp) {
        const auto lock = h5::LibraryLock();
        detail::WriteRunFileTo(tmp, path, data);
    });
}

RunData ReadRunFile(const fs::path& path) {
    const auto lock = h5::LibraryLock();
    return ReadAsInput(path.string(), [&] {
        const h5::FileReader r(path.string());
        return detail::ReadRun(r);
    });
}

RunData ReadRunFileImage(std::string_view bytes, const std::string& name) {
    const auto lock = h5::LibraryLock();
    return ReadAsInput(name, [&] {
        const h5::FileReader r(bytes.data(), bytes.size(), name);
        return detail::ReadRun(r);
    });
}

RunMaps ReadRunMaps(const fs::path& path) {
    const auto lock = h5::LibraryLock();
    const h5::FileReader r(path.string());
    detail::CheckVersion(r);
    return detail::ReadMaps(r);
}

void AddRunMaps(const fs::path& path, const RunMaps& maps) {
    RunData data = ReadRunFile(path);
    RunMaps& stored = data.maps;
    if (maps.grid) {
        if (stored.grid && !(*stored.grid == *maps.grid)) {
            throw MakeInputError(path.string(), "/maps", "",
                                 "new layers must use the stored grid (origin, cell size, " +
                                     std::to_string(stored.grid->rows) + " x " +
                                     std::to_string(stored.grid->cols) + " cells)");
        }
        stored.grid = maps.grid;
    }
    if (maps.elevation_m) {
        stored.elevation_m = maps.elevation_m;
    }
    if (maps.certainty) {
        stored.certainty = maps.certainty;
    }
    if (maps.truth_m) {
        stored.truth_m = maps.truth_m;
    }
    if (maps.cas_classes) {
        stored.cas_classes = maps.cas_classes;
    }
    for (const auto& [method, map] : maps.filtered) {
        stored.filtered[method] = map;
    }
    WriteRunFile(path, data);
}

}  // namespace casmap::io
