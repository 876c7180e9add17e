// ActiveWindowConfig's checks and LookAheadRows (mapper/active_window.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/mapper/active_window.hpp"

namespace casmap::mapper {
namespace {

constexpr const char* kWhere = "active window";

}  // namespace

void ActiveWindowConfig::Validate() const {
    const core::Check check(kWhere);
    const int k = cas.k;
    check.That(k >= 1, "cas.k", k, ">= 1");
    check.That(rows >= 2 * k + 2, "rows", rows, ">= 2 k + 2 (room for a filtered row's window)");
    check.That(cols >= 2 * k + 1, "cols", cols, ">= 2 k + 1");
    check.That(
        m >= k + 1 && m <= rows - k, "m", m,
        "in [k + 1, rows - k]: the filtered row R - m and its k neighbours lie in the window");
    check.That(std::isfinite(cell_m) && cell_m > 0.0, "cell_m", cell_m, "finite and > 0");
    check.That(std::isfinite(origin_x_m), "origin_x_m", origin_x_m, "finite");
    check.That(std::isfinite(origin_y_m), "origin_y_m", origin_y_m, "finite");
    check.That(std::isfinite(heading_step_rad) && heading_step_rad > 0.0 &&
                   heading_step_rad <= std::numbers::pi / 2.0,
               "heading_step_rad", heading_step_rad, "in (0, pi/2]");
    check.That(std::isfinite(delta_l_m) && delta_l_m >= 0.0, "delta_l_m", delta_l_m,
               "finite and >= 0");
    check.That(a >= 1, "a", a, "a positive integer");
    check.That(std::isfinite(scan_period_s) && scan_period_s > 0.0, "scan_period_s", scan_period_s,
               "finite and > 0");
    check.That(cas.a == a, "cas.a", cas.a, "must equal a (Eq. 8 uses the mapper's increment)");
    check.That(cas.cell_m == cell_m, "cas.cell_m", cas.cell_m, "must equal cell_m (Eq. 8 s)");
    check.That(cas.normalise == Normalise::kWindow, "cas.normalise", 1.0,
               "window: a whole-map maximum does not exist on a moving window");
    check.That(max_rows_per_scan >= 1, "max_rows_per_scan", max_rows_per_scan, ">= 1");
    check.That(std::isfinite(obstacle_cell_m) && obstacle_cell_m > 0.0, "obstacle_cell_m",
               obstacle_cell_m, "finite and > 0");
    if (consensus) {
        consensus->Validate(kWhere);  // "active window: consensus.<field> ..."
    }
}

int LookAheadRows(const ActiveWindowConfig& config,
                  double height_m,
                  double pitch_rad,
                  double max_height_m) {
    const int k = config.cas.k;
    const double tan_p = std::tan(pitch_rad);
    int f = k;  // nearest admissible filtered row
    if (tan_p > 0.0 && height_m > max_height_m) {
        const double d = (height_m - max_height_m) / tan_p;
        const double rows = std::floor(d / config.cell_m) - k - 1;
        f = static_cast<int>(
            std::clamp(rows, static_cast<double>(k), static_cast<double>(config.rows - k - 1)));
    }
    return config.rows - f;
}

}  // namespace casmap::mapper
