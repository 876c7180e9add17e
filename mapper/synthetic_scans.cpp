#include "casmap/mapper/synthetic_scans.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace casmap::mapper {
namespace {

constexpr double kMaxRangeM = 8.0;

// Distance along the unit ray o + t d to an axis-aligned box [x0,x1]x[y0,y1]x[0,h], or +inf.
double RayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const SyntheticBox& b) {
    double t0 = 0.0;
    double t1 = std::numeric_limits<double>::infinity();
    const double lo[3] = {b.x0_m, b.y0_m, 0.0};
    const double hi[3] = {b.x1_m, b.y1_m, b.height_m};
    for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-15) {
            if (o[k] < lo[k] || o[k] > hi[k]) {
                return std::numeric_limits<double>::infinity();
            }
            continue;
        }
        double ta = (lo[k] - o[k]) / d[k];
        double tb = (hi[k] - o[k]) / d[k];
        if (ta > tb) {
            std::swap(ta, tb);
        }
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1 && t0 > 0.0 ? t0 : std::numeric_limits<double>::infinity();
}

core::Pose PoseAtTime(const SyntheticDrive& d, double t) {
    double x = d.start_x_m;
    double y = d.start_y_m;
    const double yaw = d.start_yaw_rad + d.yaw_rate_rad_s * t;
    if (std::abs(d.yaw_rate_rad_s) < 1e-12) {
        x += d.speed_m_s * t * std::cos(d.start_yaw_rad);
        y += d.speed_m_s * t * std::sin(d.start_yaw_rad);
    } else {
        const double r = d.speed_m_s / d.yaw_rate_rad_s;
        x += r * (std::sin(yaw) - std::sin(d.start_yaw_rad));
        y -= r * (std::cos(yaw) - std::cos(d.start_yaw_rad));
    }
    return core::PoseFromXyzRpy(Eigen::Vector3d(x, y, d.height_m),
                                Eigen::Vector3d(0.0, d.pitch_rad, yaw));
}

}  // namespace

SyntheticRun BuildSyntheticRun(const SyntheticDrive& drive) {
    SyntheticRun run;
    std::vector<core::TimedPose> samples;
    const auto n_poses = static_cast<int>(std::ceil(drive.duration_s * drive.pose_rate_hz));
    for (int n = 0; n <= n_poses; ++n) {
        const double t = n / drive.pose_rate_hz;
        samples.push_back({t, PoseAtTime(drive, t)});
    }
    run.poses = core::Trajectory(std::move(samples));
    const double period_s = 1.0 / 75.0;
    const double deg = std::numbers::pi / 180.0;
    int valid = 0;
    std::mt19937_64 noise(20260511);  // range noise: a fixed sequence
    // Per beam: the height of the box top it hit in the last scan (0: none).
    std::vector<double> top_before(181, 0.0);
    for (int n = 0;; ++n) {
        core::Scan s;
        s.stamp_s = n * period_s;
        s.start_angle_rad = -90.0 * deg;
        s.angle_step_rad = deg;
        s.beam_period_s = period_s / 360.0;
        s.beams.resize(181);
        if (s.BeamTime(180) > run.poses.EndTime()) {
            break;
        }
        for (std::size_t i = 0; i < s.beams.size(); ++i) {
            const core::Pose p = PoseAtTime(drive, s.BeamTime(i));
            const double a = s.BeamAngle(i);
            const Eigen::Vector3d dir = p.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
            const double floor = dir.z() < -1e-9 ? -p.translation.z() / dir.z()
                                                 : std::numeric_limits<double>::infinity();
            double r = floor;
            double top = 0.0;  // height of the box top hit, if the hit is on a top
            for (const SyntheticBox& b : drive.boxes) {
                const double t = RayBox(p.translation, dir, b);
                if (t < r) {
                    r = t;
                    const bool on_top =
                        std::abs(p.translation.z() + t * dir.z() - b.height_m) < 1e-9;
                    top = on_top ? b.height_m : 0.0;
                }
            }
            if (drive.mixed_far_edges && r == floor && top_before[i] > 0.0 && r <= kMaxRangeM) {
                r = 0.5 * ((top_before[i] - p.translation.z()) / dir.z() + floor);  // mid-air
            }
            top_before[i] = top;
            core::Beam& beam = s.beams[i];
            if (r <= kMaxRangeM) {
                ++valid;
                const bool spike = drive.spike_every > 0 && valid % drive.spike_every == 0;
                if (drive.range_noise_m > 0.0) {
                    r += drive.range_noise_m *
                         (2.0 * std::generate_canonical<double, 53>(noise) - 1.0);
                }
                beam.range_m = static_cast<float>(spike ? std::max(0.05, r - 0.3) : r);
                beam.status = core::BeamStatus::kOk;
            }
        }
        run.scans.push_back(std::move(s));
    }
    return run;
}

}  // namespace casmap::mapper
