#include "casmap/mapper/active_window.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/mapper/beam_geometry.hpp"

namespace casmap::mapper {
namespace {

std::int64_t Mod(std::int64_t a, std::int64_t n) {
    const std::int64_t r = a % n;
    return r < 0 ? r + n : r;
}

double WrapPi(double x) { return std::remainder(x, 2.0 * std::numbers::pi); }

// Heading of the sensor's x axis projected on the world x-y plane.
double HeadingOf(const core::Pose& p) {
    const Eigen::Matrix3d r = p.rotation.toRotationMatrix();
    return std::atan2(r(1, 0), r(0, 0));
}

}  // namespace

ActiveWindow::ActiveWindow(const ActiveWindowConfig& config)
    : config_(config), obstacles_(config.obstacle_cell_m, config.origin_x_m, config.origin_y_m) {
    config_.Validate();
    filter_index_ = config_.rows - config_.m;
    const std::size_t n = static_cast<std::size_t>(config_.rows) * config_.cols;
    h_.assign(n, 0.0F);
    c_.assign(n, 0.0F);
    registered_.assign(n, 0);
    h_back_.assign(n, 0.0F);
    c_back_.assign(n, 0.0F);
    registered_back_.assign(n, 0);
    row_data_.assign(static_cast<std::size_t>(config_.rows), 0);
    row_data_back_.assign(static_cast<std::size_t>(config_.rows), 0);
    if (config_.consensus) {
        cons_.Assign(n);
        cons_back_.Assign(n);
    }
    const int span = 2 * config_.cas.k + 1;
    band_h_ = core::MapF(span, config_.cols, 0.0F);
    band_c_ = core::MapF(span, config_.cols, 0.0F);
}

std::size_t ActiveWindow::Slot(std::int64_t a, std::int64_t b) const {
    return static_cast<std::size_t>(Mod(a, config_.rows) * config_.cols + Mod(b, config_.cols));
}

Eigen::Vector2d ActiveWindow::CellCentre(std::int64_t a, std::int64_t b) const {
    const double u = (static_cast<double>(a) + 0.5) * config_.cell_m;
    const double v = (static_cast<double>(b) + 0.5) * config_.cell_m;
    return {config_.origin_x_m + cos_ * u - sin_ * v, config_.origin_y_m + sin_ * u + cos_ * v};
}

void ActiveWindow::ClearRow(std::int64_t a) {
    const auto r = static_cast<std::size_t>(Mod(a, config_.rows));
    if (row_data_[r] == 0) {
        return;  // all zero already
    }
    row_data_[r] = 0;
    const std::size_t off = r * static_cast<std::size_t>(config_.cols);
    std::fill_n(h_.begin() + static_cast<std::ptrdiff_t>(off), config_.cols, 0.0F);
    std::fill_n(c_.begin() + static_cast<std::ptrdiff_t>(off), config_.cols, 0.0F);
    std::fill_n(registered_.begin() + static_cast<std::ptrdiff_t>(off), config_.cols, 0);
    if (!cons_.empty()) {
        cons_.Clear(off, static_cast<std::size_t>(config_.cols));
    }
}

void ActiveWindow::ClearCol(std::int64_t b) {
    const auto j = static_cast<std::size_t>(Mod(b, config_.cols));
    for (std::size_t i = 0; i < static_cast<std::size_t>(config_.rows); ++i) {
        const std::size_t s = i * static_cast<std::size_t>(config_.cols) + j;
        h_[s] = 0.0F;
        c_[s] = 0.0F;
        registered_[s] = 0;
        if (!cons_.empty()) {
            cons_.Clear(s, 1);
        }
    }
}

void ActiveWindow::Place(double heading_rad, std::int64_t a0, std::int64_t b0) {
    std::fill(h_.begin(), h_.end(), 0.0F);
    std::fill(c_.begin(), c_.end(), 0.0F);
    std::fill(registered_.begin(), registered_.end(), 0);
    std::fill(row_data_.begin(), row_data_.end(), 0);
    if (!cons_.empty()) {
        cons_.Clear(0, h_.size());
    }
    heading_rad_ = heading_rad;
    cos_ = std::cos(heading_rad);
    sin_ = std::sin(heading_rad);
    a0_ = a0;
    b0_ = b0;
    next_filter_row_ = a0 + filter_index_;
    placed_ = true;
}

void ActiveWindow::Advance(std::int64_t a0, std::int64_t b0) {
    const std::int64_t rows = config_.rows;
    const std::int64_t cols = config_.cols;
    // Rows entering ahead (forward) or behind (reverse) start unknown.
    const std::int64_t da = a0 - a0_;
    for (std::int64_t i = 0; i < std::min(std::abs(da), rows); ++i) {
        ClearRow(da > 0 ? a0_ + rows + i : a0 + i);
    }
    const std::int64_t db = b0 - b0_;
    for (std::int64_t j = 0; j < std::min(std::abs(db), cols); ++j) {
        ClearCol(db > 0 ? b0_ + cols + j : b0 + j);
    }
    a0_ = a0;
    b0_ = b0;
    const std::int64_t k = config_.cas.k;
    if (next_filter_row_ < a0_ + k) {  // their neighbourhood left before they were due
        stats_.rows_skipped += static_cast<std::uint64_t>(a0_ + k - next_filter_row_);
        next_filter_row_ = a0_ + k;
    }
}

bool ActiveWindow::SourceRowsHoldData(double x_rel, double sd, std::int64_t b0) const {
    // A new row's centres lie on a line in the old frame; its old-row span runs between the
    // first and last column's rows. x_rel: old row coordinate of the row's (u, 0) point.
    const double v0 = static_cast<double>(b0) + 0.5;
    const double v1 = v0 + static_cast<double>(config_.cols - 1);
    const double r0 = x_rel - sd * v0;
    const double r1 = x_rel - sd * v1;
    const auto lo = static_cast<std::int64_t>(std::max(std::floor(std::min(r0, r1)), 0.0));
    const auto hi = static_cast<std::int64_t>(
        std::min(std::floor(std::max(r0, r1)), static_cast<double>(config_.rows - 1)));
    for (std::int64_t r = lo; r <= hi; ++r) {
        if (row_data_[static_cast<std::size_t>(Mod(a0_ + r, config_.rows))] != 0) {
            return true;
        }
    }
    return false;
}

void ActiveWindow::Resample(double heading_rad, std::int64_t a0, std::int64_t b0) {
    // Nearest neighbour: each new cell takes elevation, certainty and the registered flag of
    // the old cell containing its centre (no interpolation: heights of mixed pixels must not
    // be smeared before CAS sees them); centres outside the old window start unknown. Only
    // rows from R - m - k on are resampled: the rows behind are filtered and no longer read.
    const std::int64_t rows = config_.rows;
    const std::int64_t cols = config_.cols;
    const int k = config_.cas.k;
    const double d = heading_rad - heading_rad_;
    const double cd = std::cos(d);
    const double sd = std::sin(d);
    // Old-frame cell coordinates (units of cells, relative to the old window's corner) of the
    // new cell centres: rotate by the heading change; one step along a row adds (-sd, cd).
    // floor(v) as int(v + kBias) - kBias: exact for |v| < kBias, no libm call per cell.
    constexpr double kBias = 1 << 20;
    const std::int64_t old_row_slot0 = Mod(a0_, rows);
    const std::int64_t old_col_slot0 = Mod(b0_, cols);
    std::int64_t first_pending = -1;  // first row behind R-m holding an unregistered cell
    const std::int64_t first_row = filter_index_ - k;
    const bool consensus = !cons_.empty();
    for (std::int64_t i = 0; i < rows; ++i) {
        const std::int64_t a = a0 + i;
        const auto to_slot = static_cast<std::size_t>(Mod(a, rows));
        const auto to_row = to_slot * static_cast<std::size_t>(cols);
        float* h_to = &h_back_[to_row];
        float* c_to = &c_back_[to_row];
        std::uint8_t* r_to = &registered_back_[to_row];
        if (row_data_back_[to_slot] != 0) {  // rows flagged empty are all zero already
            std::fill_n(h_to, cols, 0.0F);
            std::fill_n(c_to, cols, 0.0F);
            std::fill_n(r_to, cols, std::uint8_t{0});
            if (consensus) {
                cons_back_.Clear(to_row, static_cast<std::size_t>(cols));
            }
            row_data_back_[to_slot] = 0;
        }
        if (i < first_row ||
            !SourceRowsHoldData(cd * (static_cast<double>(a) + 0.5) - static_cast<double>(a0_), sd,
                                b0)) {
            continue;
        }
        row_data_back_[to_slot] = 1;
        const double u = static_cast<double>(a) + 0.5;
        const double v0 = static_cast<double>(b0) + 0.5;
        double x = cd * u - sd * v0 - static_cast<double>(a0_) + kBias;
        double y = sd * u + cd * v0 - static_cast<double>(b0_) + kBias;
        std::int64_t to_col = Mod(b0, cols);
        for (std::int64_t j = 0; j < cols; ++j, x -= sd, y += cd) {
            const std::int64_t ro = static_cast<std::int64_t>(x) - static_cast<std::int64_t>(kBias);
            const std::int64_t co = static_cast<std::int64_t>(y) - static_cast<std::int64_t>(kBias);
            const std::int64_t tc = to_col;
            to_col = to_col + 1 == cols ? 0 : to_col + 1;
            if (ro < 0 || ro >= rows || co < 0 || co >= cols) {
                continue;
            }
            std::int64_t fr = old_row_slot0 + ro;
            fr = fr >= rows ? fr - rows : fr;
            std::int64_t fc = old_col_slot0 + co;
            fc = fc >= cols ? fc - cols : fc;
            const auto from = static_cast<std::size_t>(fr * cols + fc);
            const auto t = static_cast<std::size_t>(tc);
            h_to[t] = h_[from];
            c_to[t] = c_[from];
            r_to[t] = registered_[from];
            if (consensus) {
                cons_back_.CopyCell(cons_, from, to_row + t);
            }
            if (first_pending < 0 && i >= k && i < filter_index_ && c_[from] > 0.0F &&
                registered_[from] == 0) {
                first_pending = i;
            }
        }
    }
    h_.swap(h_back_);
    c_.swap(c_back_);
    registered_.swap(registered_back_);
    row_data_.swap(row_data_back_);
    cons_.swap(cons_back_);
    heading_rad_ = heading_rad;
    cos_ = std::cos(heading_rad);
    sin_ = std::sin(heading_rad);
    a0_ = a0;
    b0_ = b0;
    // Cells that were ahead of the filter line and are now behind it get filtered now.
    next_filter_row_ = a0 + (first_pending >= 0 ? first_pending : filter_index_);
    ++stats_.turns;
}

void ActiveWindow::MoveTo(const core::Pose& world_T_sensor) {
    const double step = config_.heading_step_rad;
    const double heading = HeadingOf(world_T_sensor);
    double frame = heading_rad_;
    const bool turn = !placed_ || std::abs(WrapPi(heading - heading_rad_)) > 0.75 * step;
    if (turn) {
        frame = WrapPi(std::round(heading / step) * step);
        if (std::abs(frame) < 1e-12) {
            frame = 0.0;  // exactly the unrotated lattice
        }
    }
    const double c = turn ? std::cos(frame) : cos_;
    const double s = turn ? std::sin(frame) : sin_;
    const double x = world_T_sensor.translation.x() - config_.origin_x_m;
    const double y = world_T_sensor.translation.y() - config_.origin_y_m;
    const auto a = static_cast<std::int64_t>(std::floor((c * x + s * y) / config_.cell_m));
    const auto b = static_cast<std::int64_t>(std::floor((-s * x + c * y) / config_.cell_m));
    const std::int64_t a0 = a;
    const std::int64_t b0 = b - config_.cols / 2;
    if (!placed_) {
        Place(frame, a0, b0);
    } else if (turn) {
        Resample(frame, a0, b0);
    } else {
        Advance(a0, b0);
    }
}

void ActiveWindow::MapPoint(const Eigen::Vector3d& p, double dz_max_m) {
    // Same expression as GridGeometry::CellOf when the frame heading is 0 (cos 1, sin 0).
    const double x = p.x() - config_.origin_x_m;
    const double y = p.y() - config_.origin_y_m;
    const double fa = std::floor((cos_ * x + sin_ * y) / config_.cell_m);
    const double fb = std::floor((-sin_ * x + cos_ * y) / config_.cell_m);
    const double i = fa - static_cast<double>(a0_);
    const double j = fb - static_cast<double>(b0_);
    if (!(i >= 0.0 && j >= 0.0 && i < config_.rows && j < config_.cols)) {
        ++stats_.beams.beams_outside;  // also NaN
        return;
    }
    if (i < filter_index_) {
        ++stats_.beams_behind;
        return;
    }
    const auto a = static_cast<std::int64_t>(fa);
    if (a - config_.cas.k < next_filter_row_) {
        ++stats_.beams_late;
    }
    row_data_[static_cast<std::size_t>(Mod(a, config_.rows))] = 1;
    const std::size_t slot = Slot(a, static_cast<std::int64_t>(fb));
    if (cons_.empty()) {
        detail::UpdateCell(h_[slot], c_[slot], p.z(), dz_max_m, config_.a);
    } else {
        cons_.Update(slot, h_[slot], c_[slot], p.z(), dz_max_m, config_.a, false,
                     *config_.consensus);
    }
    ++stats_.beams.beams_mapped;
}

void ActiveWindow::FilterRow(std::int64_t a, FilteredRow& out) {
    const int k = config_.cas.k;
    const auto cols = static_cast<std::size_t>(config_.cols);
    const auto start = static_cast<std::size_t>(Mod(b0_, config_.cols));
    // Unroll the 2k+1 rows around `a` into a band starting at lattice column b0.
    for (int di = -k; di <= k; ++di) {
        const std::size_t src = static_cast<std::size_t>(Mod(a + di, config_.rows)) * cols;
        const std::size_t dst = static_cast<std::size_t>(di + k) * cols;
        std::memcpy(&band_h_.data[dst], &h_[src + start], (cols - start) * sizeof(float));
        std::memcpy(&band_h_.data[dst + cols - start], &h_[src], start * sizeof(float));
        std::memcpy(&band_c_.data[dst], &c_[src + start], (cols - start) * sizeof(float));
        std::memcpy(&band_c_.data[dst + cols - start], &c_[src], start * sizeof(float));
    }
    CasFilterInto(band_h_, band_c_, config_.cas, band_out_);
    const std::size_t mid = static_cast<std::size_t>(k) * cols;
    out.row = a;
    out.first_col = b0_;
    out.heading_rad = heading_rad_;
    out.elevation.assign(
        band_out_.elevation.data.begin() + static_cast<std::ptrdiff_t>(mid),
        band_out_.elevation.data.begin() + static_cast<std::ptrdiff_t>(mid + cols));
    out.raw.assign(band_h_.data.begin() + static_cast<std::ptrdiff_t>(mid),
                   band_h_.data.begin() + static_cast<std::ptrdiff_t>(mid + cols));
    out.certainty.assign(band_c_.data.begin() + static_cast<std::ptrdiff_t>(mid),
                         band_c_.data.begin() + static_cast<std::ptrdiff_t>(mid + cols));
    out.classes.assign(band_out_.classes.data.begin() + static_cast<std::ptrdiff_t>(mid),
                       band_out_.classes.data.begin() + static_cast<std::ptrdiff_t>(mid + cols));
    // Register the interior cells that hold something: observed (c > 0) or filled by CAS.
    constexpr auto kFilled = static_cast<std::uint8_t>(PixelClass::kFilled);
    for (std::size_t j = static_cast<std::size_t>(k); j + static_cast<std::size_t>(k) < cols; ++j) {
        const std::int64_t b = b0_ + static_cast<std::int64_t>(j);
        const std::size_t slot = Slot(a, b);
        if (registered_[slot] != 0 || (out.certainty[j] <= 0.0F && out.classes[j] != kFilled)) {
            continue;
        }
        const Eigen::Vector2d centre = CellCentre(a, b);
        obstacles_.Register(centre.x(), centre.y(), out.elevation[j], out.certainty[j]);
        registered_[slot] = 1;
        row_data_[static_cast<std::size_t>(Mod(a, config_.rows))] = 1;
    }
    ++stats_.rows_filtered;
}

void ActiveWindow::FilterDueRows() {
    int budget = config_.max_rows_per_scan;
    while (next_filter_row_ <= a0_ + filter_index_ && budget-- > 0) {
        if (n_filtered_ == filtered_.size()) {
            filtered_.emplace_back();
        }
        FilterRow(next_filter_row_, filtered_[n_filtered_]);
        ++n_filtered_;
        ++next_filter_row_;
    }
}

std::span<const FilteredRow> ActiveWindow::AddScan(const core::Scan& scan,
                                                   const core::Trajectory& world_T_sensor,
                                                   std::span<const std::uint8_t> keep) {
    if (!keep.empty() && keep.size() != scan.beams.size()) {
        throw MakeInputError(
            "active window", "keep labels", std::to_string(keep.size()),
            "must have one entry per beam (" + std::to_string(scan.beams.size()) + ")");
    }
    n_filtered_ = 0;
    ++stats_.scans;
    const std::optional<core::Pose> pose =
        world_T_sensor.empty() ? std::nullopt : world_T_sensor.PoseAt(scan.stamp_s);
    if (!pose) {
        ++stats_.scans_no_pose;
        stats_.beams.beams_seen += scan.beams.size();
        stats_.beams.beams_no_pose += scan.beams.size();
        return {};
    }
    MoveTo(*pose);
    dirs_.Update(scan);
    detail::ForEachBeamPoint(
        scan, world_T_sensor, dirs_, config_.scan_period_s, config_.delta_l_m, stats_.beams,
        [this](const Eigen::Vector3d& p_world, double dz_max_m) { MapPoint(p_world, dz_max_m); },
        keep);
    FilterDueRows();
    return {filtered_.data(), n_filtered_};
}

void ActiveWindow::Snapshot(core::MapF& elevation, core::MapF& certainty) const {
    elevation = core::MapF(config_.rows, config_.cols, 0.0F);
    certainty = core::MapF(config_.rows, config_.cols, 0.0F);
    for (int i = 0; i < config_.rows; ++i) {
        for (int j = 0; j < config_.cols; ++j) {
            const std::size_t s = Slot(a0_ + i, b0_ + j);
            elevation.at(i, j) = h_[s];
            certainty.at(i, j) = c_[s];
        }
    }
}

}  // namespace casmap::mapper
