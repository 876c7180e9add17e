#include "casmap/sim/simulator.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/sensor_models/scratch_array.hpp"

namespace casmap::sim {
namespace {

using sensor_models::kMaxSubrays;
using sensor_models::Lms200Model;
using sensor_models::PulseContext;
using sensor_models::PulseResult;
using sensor_models::ScratchArray;

// Fills beam i of `out` from a pose per beam time. All sub-rays of the scan are traced in one
// batch (consecutive pulses share Embree packets), then each pulse's return is formed.
template <class PoseAtBeam>
ScanResult CastScanImpl(const World& world,
                        const Lms200Model& model,
                        double stamp_s,
                        std::uint64_t scan_index,
                        const PoseAtBeam& pose_at) {
    ScanResult out;
    out.scan = model.MakeScan(stamp_s);
    const std::size_t n = model.BeamCount();
    const std::size_t m = model.SubrayCount();
    out.truth.labels.resize(n);
    out.truth.true_range_m.resize(n);
    // Per-thread buffers, reused scan after scan (every element read is written first).
    thread_local RayBatch ray_buffer;
    thread_local HitBatch hit_buffer;
    thread_local std::vector<Eigen::Vector3d> axis_buffer;
    RayBatch& rays = ray_buffer;
    HitBatch& hits = hit_buffer;
    std::vector<Eigen::Vector3d>& axes = axis_buffer;
    rays.Resize(n * m);
    rays.tmax_m = static_cast<float>(model.TraceRangeM());
    axes.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const sensor_models::PulseFrame frame =
            model.PulseBasis(scan_index, i, pose_at(i, out.scan.BeamTime(i)));
        axes[i] = frame.axis;
        const std::size_t first = i * m;
        model.SubraysSoA(frame, rays.ox.data() + first, rays.oy.data() + first,
                         rays.oz.data() + first, rays.dx.data() + first, rays.dy.data() + first,
                         rays.dz.data() + first);
    }
    if (m == 1) {
        world.CastBatchSingly(rays, hits);  // the ideal scanner: one ray per pulse
    } else {
        world.CastBatch(rays, hits);
    }
    for (std::size_t i = 0; i < n; ++i) {
        PulseContext pulse;
        pulse.scan_index = scan_index;
        pulse.beam = static_cast<std::uint32_t>(i);
        pulse.time_s = out.scan.BeamTime(i);
        pulse.beam_direction_world = axes[i];
        const std::size_t first = i * m;
        const sensor_models::SubrayHitArrays sub_hits{
            hits.distance_m.data() + first,   hits.cos_incidence.data() + first,
            hits.reflectivity.data() + first, hits.retro_reflective.data() + first,
            hits.object_id.data() + first,    m};
        const PulseResult r = model.FormReturn(pulse, sub_hits);
        out.scan.beams[i] = r.beam;
        out.truth.labels[i] = r.label;
        out.truth.true_range_m[i] = r.true_range_m;
    }
    return out;
}

std::string Seconds(double s) {
    std::ostringstream o;
    o.precision(9);
    o << s;
    return o.str();
}

}  // namespace

PulseResult CastPulse(const World& world,
                      const Lms200Model& model,
                      const core::Pose& world_T_sensor,
                      PulseContext pulse) {
    const std::size_t n = model.SubrayCount();
    const auto tmax = static_cast<float>(model.TraceRangeM());
    const sensor_models::PulseFrame frame =
        model.PulseBasis(pulse.scan_index, pulse.beam, world_T_sensor);
    ScratchArray<Ray, kMaxSubrays> rays;
    model.ForEachSubray(frame, [&rays, tmax](std::size_t, const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& dir) {
        rays.EmplaceBack(origin.cast<float>(), dir.cast<float>(), tmax);
    });
    pulse.beam_direction_world = frame.axis;
    ScratchArray<Hit, kMaxSubrays> hits;
    hits.Construct(n);
    if (n == 1) {
        hits[0] = world.CastOne(rays[0]);
    } else {
        world.CastPacket(std::as_const(rays).span(), hits.span());
    }
    ScratchArray<sensor_models::SubrayHit, kMaxSubrays> sub_hits;
    for (std::size_t i = 0; i < n; ++i) {
        const Hit& h = hits[i];
        if (!h.valid()) {
            sub_hits.EmplaceBack();  // a miss
            continue;
        }
        sub_hits.EmplaceBack(static_cast<double>(h.distance_m),
                             std::abs(static_cast<double>(h.normal.dot(rays[i].direction))),
                             static_cast<double>(h.reflectivity), h.object_id, h.retro_reflective);
    }
    return model.FormReturn(pulse, std::as_const(sub_hits).span());
}

ScanResult CastScan(const World& world,
                    const Lms200Model& model,
                    const core::Trajectory& world_T_sensor,
                    double stamp_s,
                    std::uint64_t scan_index) {
    const double last_offset = model.MaxBeamTimeOffsetS();
    if (world_T_sensor.empty() || !(stamp_s >= world_T_sensor.StartTime()) ||
        !(stamp_s + last_offset <= world_T_sensor.EndTime())) {
        const std::string span = world_T_sensor.empty()
                                     ? std::string("empty")
                                     : Seconds(world_T_sensor.StartTime()) + ".." +
                                           Seconds(world_T_sensor.EndTime()) + " s";
        throw MakeInputError("trajectory", "scan " + std::to_string(scan_index) + " stamp_s",
                             Seconds(stamp_s),
                             "the scan's beams must lie within the trajectory (" + span + ")");
    }
    // The beams' times are close: each search starts at the last, and beams between the same
    // two samples share the slerp's acos and sin.
    core::Trajectory::Cursor cursor;
    return CastScanImpl(world, model, stamp_s, scan_index,
                        [&](std::size_t, double t) { return *world_T_sensor.PoseAt(t, cursor); });
}

ScanResult CastScanAt(const World& world,
                      const Lms200Model& model,
                      const core::Pose& world_T_sensor,
                      double stamp_s,
                      std::uint64_t scan_index) {
    return CastScanImpl(world, model, stamp_s, scan_index,
                        [&](std::size_t, double) { return world_T_sensor; });
}

std::vector<ScanResult> Simulate(const World& world,
                                 const Lms200Model& model,
                                 const core::Trajectory& world_T_sensor,
                                 const SimulateOptions& options) {
    const double period = options.period_s > 0.0 ? options.period_s : model.ScanPeriodS();
    std::vector<ScanResult> scans(options.scan_count);
    core::ProgressCounter progress(options.progress, options.scan_count);
    core::ParallelFor(options.scan_count, options.threads, [&](std::size_t k) {
        scans[k] = CastScan(world, model, world_T_sensor,
                            options.start_s + static_cast<double>(k) * period,
                            options.first_scan_index + k);
        progress.Advance();
    });
    return scans;
}

}  // namespace casmap::sim
