#pragma once

// Internals shared by sweep.cpp (options), sweep_run.cpp (the runs) and sweep_report.cpp.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline::detail {

/// Grid points, row-major over the axes (the first axis varying slowest); InputError naming
/// "axes" beyond 10000 points.
[[nodiscard]] std::vector<std::vector<double>> GridPoints(const std::vector<SweepAxis>& axes);

/// The filter overrides of one grid point (NAME=VALUE for FilterParams::Set): fixed, then axes.
[[nodiscard]] std::vector<std::string> PointOverrides(const SweepOptions& opt,
                                                      const std::vector<double>& point);

/// Index of the axis `name`, or -1.
[[nodiscard]] int AxisIndex(const SweepOptions& opt, const std::string& name);

/// Speeds to simulate (0: the rig's own).
[[nodiscard]] std::vector<double> Speeds(const SweepOptions& opt);

/// Setups per speed x test (test-major within a speed); `seed` is every setup's seed.
[[nodiscard]] std::vector<std::vector<SimSetup>> Setups(const SweepOptions& opt,
                                                        const BenchSettings& settings,
                                                        const std::vector<std::string>& tests);

/// Throws InputError naming "axes" unless `value` is allowed for the axis `name` under the
/// sweep's filter and fixed settings (used by Validate and by grid growth).
void CheckAxisValue(const SweepOptions& opt, const std::string& name, double value);

/// `v` rounded to 12 significant digits: axis values without binary noise (FROM + i STEP).
[[nodiscard]] double Snap(double v);

/// True when CheckAxisValue accepts the value.
[[nodiscard]] bool AxisValueAllowed(const SweepOptions& opt, const std::string& name, double value);

/// The map filter of opt.filter when it is one of SweepableFilters() (scored on the paper's map
/// directly); nullopt for any other pipeline name (scored through ScorePipelines).
[[nodiscard]] std::optional<mapper::FilterMethod> SweepFilter(const SweepOptions& opt);

}  // namespace casmap::pipeline::detail
