#include "casmap/io/run_file.hpp"

#include <cmath>
#include <limits>
#include <string_view>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/hdf5_util.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;
using h5::Id;

// Version 2 holds no variable-length data (no HDF5 global heap): config_yaml is a fixed-length
// string dataset and the string attributes are fixed-length. Version 1 (config_yaml a
// variable-length attribute) is still read, after a check of its global heap
// (docs/run-file.md).
constexpr std::int32_t kFormatVersion = 2;
constexpr std::int32_t kOldestFormatVersion = 1;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
namespace limits = core::limits;
const h5::DimLimit kScansLimit{limits::kMaxScans, "scans"};
const h5::DimLimit kBeamsLimit{limits::kMaxBeamsPerScan, "beams per scan"};
const h5::DimLimit kPosesLimit{limits::kMaxPoses, "poses"};
const h5::DimLimit kGridLimit{limits::kMaxGridCells, "grid cells"};

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

// ---------------------------------------------------------------------------------------------
// Writing

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

// ---------------------------------------------------------------------------------------------
// Reading

std::string Shape(const std::vector<hsize_t>& dims) {
    std::string text;
    for (std::size_t i = 0; i < dims.size(); ++i) {
        text += (i == 0 ? "" : " x ") + std::to_string(dims[i]);
    }
    return "shape " + text;
}

/// Reads an N x B dataset and checks its shape.
template <typename T>
std::vector<T> ReadBeams(const h5::FileReader& r, const std::string& name, hsize_t n, hsize_t b) {
    std::vector<hsize_t> dims;
    std::vector<T> values = r.Read<T>(name, 2, dims, {kScansLimit, kBeamsLimit});
    if (dims[0] != n || dims[1] != b) {
        throw r.Error(name, Shape(dims),
                      "must be N x B = " + std::to_string(n) + " x " + std::to_string(b) +
                          " like /scans/ranges_m and /scans/stamp_s");
    }
    return values;
}

double RequiredDouble(const h5::FileReader& r, const std::string& object, const std::string& name) {
    const std::optional<double> v = r.ReadDouble(object, name);
    if (!v || !std::isfinite(*v)) {
        throw r.Error(h5::AttributeWhere(object, name), v ? core::FormatNumber(*v) : "",
                      v ? "must be finite" : "required attribute is missing");
    }
    return *v;
}

/// Reads the shared scan geometry; `any_beam` false (an empty run) skips the range rules.
core::Scan ReadScanGeometry(const h5::FileReader& r, std::size_t beams, bool any_beam) {
    core::Scan proto;
    proto.start_angle_rad = RequiredDouble(r, "/scans", "start_angle_rad");
    proto.angle_step_rad = RequiredDouble(r, "/scans", "angle_step_rad");
    proto.beam_period_s = RequiredDouble(r, "/scans", "beam_period_s");
    if (!any_beam) {
        return proto;  // an empty run (no scans) has no scan geometry to check
    }
    if (!(proto.angle_step_rad > 0.0 && proto.angle_step_rad <= 0.1)) {
        throw r.Error(h5::AttributeWhere("/scans", "angle_step_rad"),
                      core::FormatNumber(proto.angle_step_rad), "allowed: 0 < step <= 0.1 rad");
    }
    if (!(proto.beam_period_s >= 0.0 && proto.beam_period_s <= 0.01)) {
        throw r.Error(h5::AttributeWhere("/scans", "beam_period_s"),
                      core::FormatNumber(proto.beam_period_s), "allowed: 0..0.01 s");
    }
    if (auto offsets = r.ReadDoubles("/scans", "beam_time_offset_s", limits::kMaxBeamsPerScan)) {
        if (offsets->size() != beams) {
            throw r.Error(h5::AttributeWhere("/scans", "beam_time_offset_s"),
                          std::to_string(offsets->size()) + " values",
                          "must hold one offset per beam (" + std::to_string(beams) + ")");
        }
        proto.beam_time_offset_s = std::move(*offsets);
    }
    return proto;
}

std::optional<core::Lms200Format> ReadFormat(const h5::FileReader& r) {
    const std::optional<std::string> mode = r.ReadString("/scans", "range_mode");
    const std::optional<std::string> units = r.ReadString("/scans", "range_units");
    if (!mode && !units) {
        return std::nullopt;
    }
    if (!mode || !units) {
        throw r.Error(h5::AttributeWhere("/scans", mode ? "range_units" : "range_mode"), "",
                      "range_mode and range_units come together");
    }
    core::Lms200Format format;
    if (*mode == "8m") {
        format.mode = core::RangeMode::k8m;
    } else if (*mode == "16m") {
        format.mode = core::RangeMode::k16m;
    } else if (*mode == "32m") {
        format.mode = core::RangeMode::k32m;
    } else {
        throw r.Error(h5::AttributeWhere("/scans", "range_mode"), *mode, "allowed: 8m, 16m, 32m");
    }
    if (*units != "mm" && *units != "cm") {
        throw r.Error(h5::AttributeWhere("/scans", "range_units"), *units, "allowed: mm, cm");
    }
    format.units = *units == "mm" ? core::RangeUnits::kMillimetre : core::RangeUnits::kCentimetre;
    return format;
}

std::string BeamIndex(const std::string& dataset, std::size_t k, std::size_t beams) {
    return dataset + "[" + std::to_string(k / beams) + ", " + std::to_string(k % beams) + "]";
}

void ReadScans(const h5::FileReader& r, RunData& data) {
    std::vector<hsize_t> dims;
    const std::vector<double> stamps = r.Read<double>("/scans/stamp_s", 1, dims, {kScansLimit});
    const hsize_t n = dims[0];
    const std::vector<float> ranges =
        r.Read<float>("/scans/ranges_m", 2, dims, {kScansLimit, kBeamsLimit});
    if (dims[0] != n) {
        throw r.Error("/scans/ranges_m", Shape(dims),
                      "needs one row per entry of /scans/stamp_s (" + std::to_string(n) + ")");
    }
    const hsize_t b = dims[1];
    const auto raw = ReadBeams<std::uint16_t>(r, "/scans/raw", n, b);
    const auto status = ReadBeams<std::uint8_t>(r, "/scans/status", n, b);
    const std::size_t beams = static_cast<std::size_t>(b);
    const core::Scan proto = ReadScanGeometry(r, beams, n > 0 && beams > 0);
    data.format = ReadFormat(r);
    data.scans.assign(static_cast<std::size_t>(n), proto);
    for (std::size_t i = 0; i < data.scans.size(); ++i) {
        core::Scan& s = data.scans[i];
        if (!std::isfinite(stamps[i])) {
            throw r.Error("/scans/stamp_s[" + std::to_string(i) + "]",
                          core::FormatNumber(stamps[i]), "must be finite");
        }
        if (i > 0 && !(stamps[i] > stamps[i - 1])) {
            throw r.Error("/scans/stamp_s[" + std::to_string(i) + "]",
                          core::FormatNumber(stamps[i]),
                          "stamps must increase strictly (previous " +
                              core::FormatNumber(stamps[i - 1]) + ")");
        }
        s.stamp_s = stamps[i];
        s.beams.resize(beams);
        for (std::size_t j = 0; j < beams; ++j) {
            const std::size_t k = i * beams + j;
            if (status[k] >= core::kBeamStatusCount) {
                throw r.Error(BeamIndex("/scans/status", k, beams), std::to_string(status[k]),
                              "allowed: 0..6 (BeamStatus)");
            }
            core::Beam& beam = s.beams[j];
            beam.status = static_cast<core::BeamStatus>(status[k]);
            beam.raw = raw[k];
            beam.range_m = beam.status == core::BeamStatus::kOk ? ranges[k] : kNaN;
            if (beam.status == core::BeamStatus::kOk && !(ranges[k] >= 0.0F && ranges[k] <= 1e3F)) {
                throw r.Error(BeamIndex("/scans/ranges_m", k, beams), core::FormatNumber(ranges[k]),
                              "a beam with status 0 (ok) needs a range in 0..1000 m");
            }
        }
    }
    if (!r.Has("/scans/labels")) {
        if (r.Has("/scans/true_range_m")) {
            throw r.Error("/scans/true_range_m", "", "needs /scans/labels beside it");
        }
        return;
    }
    const auto labels = ReadBeams<std::uint8_t>(r, "/scans/labels", n, b);
    std::vector<float> true_range;
    if (r.Has("/scans/true_range_m")) {
        true_range = ReadBeams<float>(r, "/scans/true_range_m", n, b);
    }
    data.truth.resize(data.scans.size());
    for (std::size_t i = 0; i < data.truth.size(); ++i) {
        core::ScanTruth& t = data.truth[i];
        t.labels.resize(beams);
        for (std::size_t j = 0; j < beams; ++j) {
            const std::size_t k = i * beams + j;
            if (labels[k] >= core::kBeamLabelCount) {
                throw r.Error(BeamIndex("/scans/labels", k, beams), std::to_string(labels[k]),
                              "allowed: 0..4 (BeamLabel)");
            }
            t.labels[j] = static_cast<core::BeamLabel>(labels[k]);
        }
        if (!true_range.empty()) {
            t.true_range_m.assign(
                true_range.begin() + static_cast<std::ptrdiff_t>(i * beams),
                true_range.begin() + static_cast<std::ptrdiff_t>((i + 1) * beams));
        }
    }
}

void ReadPoses(const h5::FileReader& r, RunData& data) {
    std::vector<hsize_t> dims;
    const std::vector<double> stamps = r.Read<double>("/poses/stamp_s", 1, dims, {kPosesLimit});
    const hsize_t p = dims[0];
    const std::vector<double> xyz =
        r.Read<double>("/poses/xyz_m", 2, dims, {kPosesLimit, {3, "x, y, z"}});
    if (dims[0] != p || dims[1] != 3) {
        throw r.Error("/poses/xyz_m", Shape(dims), "must be P x 3 with P = " + std::to_string(p));
    }
    const std::vector<double> quat =
        r.Read<double>("/poses/quat_xyzw", 2, dims, {kPosesLimit, {4, "x, y, z, w"}});
    if (dims[0] != p || dims[1] != 4) {
        throw r.Error("/poses/quat_xyzw", Shape(dims),
                      "must be P x 4 with P = " + std::to_string(p));
    }
    std::vector<core::TimedPose> samples(static_cast<std::size_t>(p));
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Eigen::Vector3d t(xyz[i * 3], xyz[i * 3 + 1], xyz[i * 3 + 2]);
        Eigen::Quaterniond q(quat[i * 4 + 3], quat[i * 4], quat[i * 4 + 1], quat[i * 4 + 2]);
        if (!t.allFinite()) {
            throw r.Error("/poses/xyz_m[" + std::to_string(i) + "]", "", "must be finite");
        }
        if (!q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-3) {
            throw r.Error("/poses/quat_xyzw[" + std::to_string(i) + "]",
                          "norm " + core::FormatNumber(q.norm(), 6), "must be a unit quaternion");
        }
        q.normalize();
        samples[i] = core::TimedPose{stamps[i], core::Pose{t, q}};
    }
    try {
        data.poses = core::Trajectory(std::move(samples));
    } catch (const InputError& e) {
        throw r.Error("/poses/stamp_s", "", e.what());
    }
}

core::MapF ReadLayer(const h5::FileReader& r,
                     const std::string& name,
                     const core::GridGeometry& g) {
    std::vector<hsize_t> dims;
    core::MapF map;
    map.data = r.Read<float>(name, 2, dims, {kGridLimit, kGridLimit});
    if (dims[0] != static_cast<hsize_t>(g.rows) || dims[1] != static_cast<hsize_t>(g.cols)) {
        throw r.Error(name, Shape(dims),
                      "must match /maps rows x cols = " + std::to_string(g.rows) + " x " +
                          std::to_string(g.cols));
    }
    map.rows = g.rows;
    map.cols = g.cols;
    return map;
}

int RequiredCount(const h5::FileReader& r, const std::string& name) {
    const std::optional<std::int64_t> v = r.ReadInteger("/maps", name);
    if (!v || *v <= 0 || *v > std::numeric_limits<int>::max()) {
        throw r.Error(h5::AttributeWhere("/maps", name), v ? std::to_string(*v) : "",
                      v ? "must be a positive count" : "required attribute is missing");
    }
    return static_cast<int>(*v);
}

RunMaps ReadMaps(const h5::FileReader& r) {
    RunMaps maps;
    if (!r.Has("/maps")) {
        return maps;
    }
    core::GridGeometry g;
    g.x0_m = RequiredDouble(r, "/maps", "origin_x_m");
    g.y0_m = RequiredDouble(r, "/maps", "origin_y_m");
    g.cell_m = RequiredDouble(r, "/maps", "cell_m");
    g.rows = RequiredCount(r, "rows");
    g.cols = RequiredCount(r, "cols");
    if (!(g.cell_m > 0.0)) {
        throw r.Error(h5::AttributeWhere("/maps", "cell_m"), core::FormatNumber(g.cell_m),
                      "must be > 0");
    }
    maps.grid = g;
    if (r.Has("/maps/elevation_m")) {
        maps.elevation_m = ReadLayer(r, "/maps/elevation_m", g);
    }
    if (r.Has("/maps/certainty")) {
        maps.certainty = ReadLayer(r, "/maps/certainty", g);
    }
    if (r.Has("/maps/truth_m")) {
        maps.truth_m = ReadLayer(r, "/maps/truth_m", g);
    }
    if (r.Has("/maps/cas_classes")) {
        std::vector<hsize_t> dims;
        core::Raster<std::uint8_t> c;
        c.data = r.Read<std::uint8_t>("/maps/cas_classes", 2, dims, {kGridLimit, kGridLimit});
        if (dims[0] != static_cast<hsize_t>(g.rows) || dims[1] != static_cast<hsize_t>(g.cols)) {
            throw r.Error("/maps/cas_classes", Shape(dims), "must match /maps rows x cols");
        }
        c.rows = g.rows;
        c.cols = g.cols;
        maps.cas_classes = std::move(c);
    }
    if (r.Has("/maps/filtered")) {
        for (const std::string& method : r.Children("/maps/filtered")) {
            maps.filtered[method] = ReadLayer(r, "/maps/filtered/" + method, g);
        }
    }
    return maps;
}

void CheckVersion(const h5::FileReader& r) {
    const std::optional<std::int64_t> version = r.ReadInteger("/", "casmap_run_format_version");
    if (version && (*version < kOldestFormatVersion || *version > kFormatVersion)) {
        throw r.Error(h5::AttributeWhere("/", "casmap_run_format_version"),
                      std::to_string(*version),
                      "this casmap reads versions " + std::to_string(kOldestFormatVersion) + ".." +
                          std::to_string(kFormatVersion));
    }
}

}  // namespace

void WriteRunFile(const fs::path& path, const RunData& data) {
    WriteAtomically(path, [&](const fs::path& tmp) {
        const auto lock = h5::LibraryLock();
        WriteRunFileTo(tmp, path, data);
    });
}

namespace {
RunData ReadRun(const h5::FileReader& r) {
    CheckVersion(r);
    RunData data;
    data.seed = r.ReadUnsigned("/", "seed");
    // Version 2: the /config_yaml dataset; version 1 and third-party files: the attribute.
    std::optional<std::string> config = r.ReadStringDataset("/config_yaml");
    if (!config) {
        config = r.ReadString("/", "config_yaml");
    }
    data.config_yaml = config.value_or("");
    ReadScans(r, data);
    ReadPoses(r, data);
    data.maps = ReadMaps(r);
    return data;
}
}  // namespace

namespace {
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

RunData ReadRunFile(const fs::path& path) {
    const auto lock = h5::LibraryLock();
    return ReadAsInput(path.string(), [&] {
        const h5::FileReader r(path.string());
        return ReadRun(r);
    });
}

RunData ReadRunFileImage(std::string_view bytes, const std::string& name) {
    const auto lock = h5::LibraryLock();
    return ReadAsInput(name, [&] {
        const h5::FileReader r(bytes.data(), bytes.size(), name);
        return ReadRun(r);
    });
}

RunMaps ReadRunMaps(const fs::path& path) {
    const auto lock = h5::LibraryLock();
    const h5::FileReader r(path.string());
    CheckVersion(r);
    return ReadMaps(r);
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
