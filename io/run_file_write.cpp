// Writing a run file (run_file.hpp): the checks of a RunData that the layout needs (one scan
// geometry, one label per beam, layers on the grid), then the HDF5 layout of docs/run-file.md.
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/run_file_detail.hpp"

namespace casmap::io::detail {
namespace {
namespace fs = std::filesystem;
using h5::Id;

std::string_view ModeName(core::RangeMode mode) {
    switch (mode) {
        case core::RangeMode::k8m:
            return "8m";
        case core::RangeMode::k16m:
            return "16m";
        case core::RangeMode::k32m:
            return "32m";
    }
    return "8m";
}

/// Scan geometry shared by all scans of a run; InputError if a scan disagrees.
std::size_t CheckScans(const fs::path& path, const RunData& data) {
    if (data.scans.empty()) {
        return 0;
    }
    const core::Scan& first = data.scans.front();
    const std::size_t beams = first.beams.size();
    if (!first.beam_time_offset_s.empty() && first.beam_time_offset_s.size() != beams) {
        throw MakeInputError(path.string(), "scans[0].beam_time_offset_s",
                             std::to_string(first.beam_time_offset_s.size()) + " offsets",
                             "must be empty or one per beam");
    }
    for (std::size_t i = 0; i < data.scans.size(); ++i) {
        const core::Scan& s = data.scans[i];
        const std::string where = "scans[" + std::to_string(i) + "]";
        if (s.beams.size() != beams) {
            throw MakeInputError(path.string(), where + ".beams",
                                 std::to_string(s.beams.size()) + " beams",
                                 "all scans of a run need " + std::to_string(beams));
        }
        if (s.start_angle_rad != first.start_angle_rad ||
            s.angle_step_rad != first.angle_step_rad || s.beam_period_s != first.beam_period_s ||
            s.beam_time_offset_s != first.beam_time_offset_s) {
            throw MakeInputError(path.string(), where, "",
                                 "angles and beam timing must equal those of scans[0]");
        }
        if (!std::isfinite(s.stamp_s)) {
            throw MakeInputError(path.string(), where + ".stamp_s", core::FormatNumber(s.stamp_s),
                                 "must be finite");
        }
    }
    if (!data.truth.empty() && data.truth.size() != data.scans.size()) {
        throw MakeInputError(path.string(), "truth", std::to_string(data.truth.size()) + " entries",
                             "must be empty or one per scan");
    }
    for (std::size_t i = 0; i < data.truth.size(); ++i) {
        const core::ScanTruth& t = data.truth[i];
        if (t.labels.size() != beams ||
            (!t.true_range_m.empty() && t.true_range_m.size() != beams)) {
            throw MakeInputError(path.string(), "truth[" + std::to_string(i) + "]", "",
                                 "needs one label (and true range, if any) per beam");
        }
    }
    return beams;
}

void WriteScans(hid_t file, const fs::path& path, const RunData& data) {
    const std::size_t beams = CheckScans(path, data);
    const std::size_t n = data.scans.size();
    const Id group = h5::CreateGroup(file, "scans");
    std::vector<double> stamps(n);
    for (std::size_t i = 0; i < n; ++i) {
        stamps[i] = data.scans[i].stamp_s;
    }
    // The N x B arrays go chunk by chunk (rows = scans) from the scans: never held whole.
    const std::vector<hsize_t> dims2 = {n, beams};
    const auto beam_rows = [&](auto value) {
        return [&data, beams, value](std::size_t first, std::size_t count, auto* out) {
            for (std::size_t i = first; i < first + count; ++i) {
                for (std::size_t j = 0; j < beams; ++j) {
                    *out++ = value(i, j);
                }
            }
        };
    };
    h5::WriteDataset(group.get(), "stamp_s", {n}, stamps);
    h5::WriteRows<float>(
        group.get(), "ranges_m", dims2, beam_rows([&](std::size_t i, std::size_t j) {
            const core::Beam& b = data.scans[i].beams[j];
            if (b.status == core::BeamStatus::kOk && !std::isfinite(b.range_m)) {
                throw MakeInputError(
                    path.string(),
                    "scans[" + std::to_string(i) + "].beams[" + std::to_string(j) + "].range_m",
                    core::FormatNumber(b.range_m), "status ok needs a finite range");
            }
            return b.status == core::BeamStatus::kOk ? b.range_m : kNaN;
        }));
    h5::WriteRows<std::uint16_t>(
        group.get(), "raw", dims2,
        beam_rows([&](std::size_t i, std::size_t j) { return data.scans[i].beams[j].raw; }));
    h5::WriteRows<std::uint8_t>(group.get(), "status", dims2,
                                beam_rows([&](std::size_t i, std::size_t j) {
                                    return static_cast<std::uint8_t>(data.scans[i].beams[j].status);
                                }));
    if (!data.truth.empty()) {
        bool have_true_range = true;
        for (const core::ScanTruth& t : data.truth) {
            have_true_range = have_true_range && !t.true_range_m.empty();
        }
        h5::WriteRows<std::uint8_t>(group.get(), "labels", dims2,
                                    beam_rows([&](std::size_t i, std::size_t j) {
                                        return static_cast<std::uint8_t>(data.truth[i].labels[j]);
                                    }));
        if (have_true_range) {
            h5::WriteRows<float>(group.get(), "true_range_m", dims2,
                                 beam_rows([&](std::size_t i, std::size_t j) {
                                     return data.truth[i].true_range_m[j];
                                 }));
        }
    }
    const core::Scan proto = n > 0 ? data.scans.front() : core::Scan{};
    h5::WriteAttribute(group.get(), "start_angle_rad", proto.start_angle_rad);
    h5::WriteAttribute(group.get(), "angle_step_rad", proto.angle_step_rad);
    h5::WriteAttribute(group.get(), "beam_period_s", proto.beam_period_s);
    if (!proto.beam_time_offset_s.empty()) {
        h5::WriteAttribute(group.get(), "beam_time_offset_s", proto.beam_time_offset_s);
    }
    if (data.format) {
        h5::WriteAttribute(group.get(), "range_mode", std::string(ModeName(data.format->mode)));
        h5::WriteAttribute(
            group.get(), "range_units",
            std::string(data.format->units == core::RangeUnits::kMillimetre ? "mm" : "cm"));
    }
}

void WritePoses(hid_t file, const core::Trajectory& poses) {
    const Id group = h5::CreateGroup(file, "poses");
    const std::size_t p = poses.size();
    const std::vector<core::TimedPose>& samples = poses.samples();
    std::vector<double> stamps(p);
    for (std::size_t i = 0; i < p; ++i) {
        stamps[i] = samples[i].stamp_s;
    }
    h5::WriteDataset(group.get(), "stamp_s", {p}, stamps);
    // Positions and orientations chunk by chunk (a 201 s table run has 201k poses).
    h5::WriteRows<double>(group.get(), "xyz_m", {p, 3},
                          [&](std::size_t first, std::size_t count, double* out) {
                              for (std::size_t i = first; i < first + count; ++i) {
                                  const Eigen::Vector3d& t = samples[i].world_T_sensor.translation;
                                  for (int k = 0; k < 3; ++k) {
                                      *out++ = t[k];
                                  }
                              }
                          });
    h5::WriteRows<double>(
        group.get(), "quat_xyzw", {p, 4}, [&](std::size_t first, std::size_t count, double* out) {
            for (std::size_t i = first; i < first + count; ++i) {
                // x, y, z, w
                const Eigen::Vector4d q = samples[i].world_T_sensor.rotation.coeffs();
                for (int k = 0; k < 4; ++k) {
                    *out++ = q[k];
                }
            }
        });
}

void CheckLayer(const fs::path& path,
                const core::GridGeometry& grid,
                const std::string& name,
                const core::MapF& map) {
    if (map.rows != grid.rows || map.cols != grid.cols ||
        map.data.size() !=
            static_cast<std::size_t>(map.rows) * static_cast<std::size_t>(map.cols)) {
        throw MakeInputError(path.string(), "maps." + name,
                             std::to_string(map.rows) + " x " + std::to_string(map.cols),
                             "must match the grid's " + std::to_string(grid.rows) + " x " +
                                 std::to_string(grid.cols));
    }
}

void WriteLayer(hid_t group, const std::string& name, const core::MapF& map) {
    h5::WriteDataset(group, name, {static_cast<hsize_t>(map.rows), static_cast<hsize_t>(map.cols)},
                     map.data);
}

void WriteMaps(hid_t file, const fs::path& path, const RunMaps& maps) {
    if (!maps.grid) {
        if (!maps.empty()) {
            throw MakeInputError(path.string(), "maps.grid", "", "map layers need a grid");
        }
        return;
    }
    const core::GridGeometry& grid = *maps.grid;
    try {
        grid.Validate();
    } catch (const InputError& e) {
        throw MakeInputError(path.string(), "maps.grid", "", e.what());
    }
    const Id group = h5::CreateGroup(file, "maps");
    h5::WriteAttribute(group.get(), "origin_x_m", grid.x0_m);
    h5::WriteAttribute(group.get(), "origin_y_m", grid.y0_m);
    h5::WriteAttribute(group.get(), "cell_m", grid.cell_m);
    h5::WriteAttribute(group.get(), "rows", static_cast<std::int32_t>(grid.rows));
    h5::WriteAttribute(group.get(), "cols", static_cast<std::int32_t>(grid.cols));
    const std::pair<const char*, const std::optional<core::MapF>*> layers[] = {
        {"elevation_m", &maps.elevation_m},
        {"certainty", &maps.certainty},
        {"truth_m", &maps.truth_m}};
    for (const auto& [name, layer] : layers) {
        if (*layer) {
            CheckLayer(path, grid, name, **layer);
            WriteLayer(group.get(), name, **layer);
        }
    }
    if (maps.cas_classes) {
        const core::Raster<std::uint8_t>& c = *maps.cas_classes;
        if (c.rows != grid.rows || c.cols != grid.cols) {
            throw MakeInputError(path.string(), "maps.cas_classes",
                                 std::to_string(c.rows) + " x " + std::to_string(c.cols),
                                 "must match the grid's " + std::to_string(grid.rows) + " x " +
                                     std::to_string(grid.cols));
        }
        h5::WriteDataset(group.get(), "cas_classes",
                         {static_cast<hsize_t>(c.rows), static_cast<hsize_t>(c.cols)}, c.data);
    }
    if (maps.filtered.empty()) {
        return;
    }
    const Id filtered = h5::CreateGroup(group.get(), "filtered");
    for (const auto& [method, map] : maps.filtered) {  // std::map: sorted, deterministic
        if (method.empty() || method.find('/') != std::string::npos || method == "." ||
            method == "..") {
            throw MakeInputError(path.string(), "maps.filtered", "'" + method + "'",
                                 "method names must be non-empty, without '/'");
        }
        CheckLayer(path, grid, "filtered." + method, map);
        WriteLayer(filtered.get(), method, map);
    }
}

}  // namespace

void WriteRunFileTo(const fs::path& tmp, const fs::path& path, const RunData& data) {
    const Id file = h5::CreateFile(tmp.string());
    h5::WriteAttribute(file.get(), "casmap_run_format_version", kFormatVersion);
    if (data.seed) {
        h5::WriteAttribute(file.get(), "seed", *data.seed);
    }
    h5::WriteStringDataset(file.get(), "config_yaml", data.config_yaml);
    WriteScans(file.get(), path, data);
    WritePoses(file.get(), data.poses);
    WriteMaps(file.get(), path, data.maps);
    h5::Check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "H5Fflush " + tmp.string());
}

}  // namespace casmap::io::detail
