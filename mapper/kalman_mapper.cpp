#include "casmap/mapper/kalman_mapper.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

void KalmanNoiseConfig::Validate() const {
    const core::Check check("kalman mapper", "kalman.");
    check.NonNegative("range_sigma_m", range_sigma_m, "allowed: >= 0");
    check.NonNegative("beam_constant_m", beam_constant_m, "allowed: >= 0");
    check.NonNegative("beam_angle_rad", beam_angle_rad, "allowed: >= 0");
    check.Positive("min_variance_m2", min_variance_m2, "allowed: > 0");
    check.Positive("mahalanobis_gate", mahalanobis_gate, "allowed: > 0");
    check.NonNegative("multi_height_noise_m2", multi_height_noise_m2, "allowed: >= 0");
}

void KalmanMapperConfig::Validate() const {
    const core::Check check("kalman mapper", "kalman.");
    grid.Validate();
    check.Positive("scan_period_s", scan_period_s, "allowed: > 0");
    KalmanNoiseConfig::Validate();
    check.That(a >= 1, "a", a, "allowed: integer >= 1");
}

KalmanMapper::KalmanMapper(const KalmanMapperConfig& config) : config_(config) {
    config_.Validate();
    const int rows = config_.grid.rows;
    const int cols = config_.grid.cols;
    elevation_ = core::MapF(rows, cols, config_.unknown == Unknown::kNaN ? kNaN : 0.0F);
    certainty_ = core::MapF(rows, cols, 0.0F);
    variance_ = core::MapF(rows, cols, kNaN);
    touched_scan_.assign(config_.grid.size(), 0);
    scan_z_.assign(config_.grid.size(), 0.0);
    scan_var_.assign(config_.grid.size(), 0.0);
}

double KalmanMapper::PointVariance(double range_m, double beam_z) const {
    const double along = config_.range_sigma_m * config_.range_sigma_m;
    const double lateral_sigma = config_.beam_constant_m + config_.beam_angle_rad * range_m;
    const double uz2 = beam_z * beam_z;
    return uz2 * along + (1.0 - uz2) * lateral_sigma * lateral_sigma;
}

void KalmanMapper::Fuse(std::size_t cell, double z_m, double variance_m2) {
    float& h = elevation_.data[cell];
    float& var = variance_.data[cell];
    float& c = certainty_.data[cell];
    const double point_var = std::max(variance_m2, config_.min_variance_m2);
    if (c == 0.0F) {
        h = static_cast<float>(z_m);
        var = static_cast<float>(point_var);
        c = static_cast<float>(config_.a);
        return;
    }
    const auto v = static_cast<double>(var);
    const double d = z_m - static_cast<double>(h);
    if (d * d > config_.mahalanobis_gate * config_.mahalanobis_gate * v) {
        var = static_cast<float>(v + config_.multi_height_noise_m2);  // outside the gate
        return;
    }
    h = static_cast<float>((v * z_m + point_var * static_cast<double>(h)) / (v + point_var));
    var = static_cast<float>(std::max(v * point_var / (v + point_var), config_.min_variance_m2));
    c += static_cast<float>(config_.a);
}

void KalmanMapper::AddScan(const core::Scan& scan,
                           const core::Trajectory& world_T_sensor,
                           std::span<const std::uint8_t> keep) {
    const std::size_t n = scan.beams.size();
    if (!keep.empty() && keep.size() != n) {
        throw MakeInputError("kalman mapper", "keep labels", std::to_string(keep.size()),
                             "must have one entry per beam (" + std::to_string(n) + ")");
    }
    stats_.beams_seen += n;
    if (world_T_sensor.empty()) {
        stats_.beams_no_pose += n;
        return;
    }
    dirs_.Update(scan);
    const detail::FillCounts counts =
        detail::FillBatch(scan, world_T_sensor, dirs_, config_.scan_period_s, keep, batch_);
    stats_.beams_not_ok += counts.not_ok;
    stats_.beams_rejected += counts.rejected;
    stats_.beams_no_pose += counts.no_pose;
    const core::GridGeometry& g = config_.grid;
    detail::ComputeBatch(0.0, batch_);
    ++scan_index_;
    touched_.clear();
    for (std::size_t j = 0; j < batch_.size; ++j) {
        const std::optional<core::Cell> at = g.CellOf(batch_.x[j], batch_.y[j]);
        if (!at) {
            ++stats_.beams_outside;
            continue;
        }
        ++stats_.beams_mapped;
        const std::size_t cell =
            static_cast<std::size_t>(at->row) * static_cast<std::size_t>(g.cols) +
            static_cast<std::size_t>(at->col);
        const double z = batch_.z[j];
        if (touched_scan_[cell] != scan_index_) {
            touched_scan_[cell] = scan_index_;
            touched_.push_back(cell);
            scan_z_[cell] = z;
            scan_var_[cell] = PointVariance(batch_.range_m[j], batch_.beam_z[j]);
        } else if (z < scan_z_[cell]) {  // the scan's lowest point of the cell
            scan_z_[cell] = z;
            scan_var_[cell] = PointVariance(batch_.range_m[j], batch_.beam_z[j]);
        }
    }
    for (const std::size_t cell : touched_) {
        Fuse(cell, scan_z_[cell], scan_var_[cell]);
    }
}

}  // namespace casmap::mapper
