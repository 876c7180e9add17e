// Reading a run file (run_file.hpp): the HDF5 layout of docs/run-file.md back into a RunData,
// every field checked (shapes against /scans/stamp_s and /maps, counts against core::limits,
// finite values, enums in range) with an InputError naming the object, value and rule.
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/run_file_detail.hpp"

namespace casmap::io::detail {
namespace {
namespace limits = core::limits;
const h5::DimLimit kScansLimit{limits::kMaxScans, "scans"};
const h5::DimLimit kBeamsLimit{limits::kMaxBeamsPerScan, "beams per scan"};
const h5::DimLimit kPosesLimit{limits::kMaxPoses, "poses"};
const h5::DimLimit kGridLimit{limits::kMaxGridCells, "grid cells"};

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

}  // namespace

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

}  // namespace casmap::io::detail
