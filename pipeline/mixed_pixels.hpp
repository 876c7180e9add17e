#pragma once

// The paper's Fig. 3 experiment with the simulated LMS 200 (`casmap mixed-pixels`): the
// scanner's straight-ahead beam at the vertical edge of a foreground plate D_f ahead, a
// background wall Delta D behind it. For each Delta D, `readings` pulses with the sensor
// stepped uniformly across the footprint (lateral offsets -a..+a, a = its 1/e^2 radius at D_f),
// each with its own pulse index (fresh footprint rotation and noise). A reading is a mixed
// pixel when it is a valid range more than 60 mm from both surfaces (as the paper).

#include <cstdint>
#include <string>
#include <vector>

#include "casmap/core/progress.hpp"
#include "casmap/sensor_models/lms200_model.hpp"

namespace casmap::pipeline {

/// The paper's Fig. 3 criterion: farther than this from both surfaces is a mixed pixel.
inline constexpr double kMixedPixelThresholdM = 0.060;

struct MixedPixelsOptions {
    double from_m = 0.2;  ///< smallest Delta D
    double to_m = 2.5;    ///< largest Delta D
    double step_m = 0.1;  ///< Delta D step
    int readings = 4000;  ///< readings per Delta D
    double foreground_m = 2.0;
    double reflectivity = 0.5;  ///< of both surfaces
    std::uint64_t seed = 0;
    std::string sensor_file;  ///< LMS 200 YAML; empty: the built-in config

    /// InputError (no `where`, the field named as here) for a bad option.
    void Validate() const;
};

struct MixedPixelsGap {
    double delta_d_m = 0.0;
    int valid = 0;  ///< readings with a valid range
    int mixed = 0;  ///< of those, mixed pixels
};

struct MixedPixelsResult {
    sensor_models::Lms200Config sensor;  ///< the config used
    std::vector<MixedPixelsGap> gaps;    ///< one per Delta D, ascending
};

/// Validates, loads the sensor file (if any) and runs every gap on `threads` threads (0: all
/// cores); the result does not depend on the thread count. `progress` counts gaps.
[[nodiscard]] MixedPixelsResult RunMixedPixels(const MixedPixelsOptions& options,
                                               int threads,
                                               const core::ProgressFn& progress = {});

/// The counts as JSON (with the sensor file and every key of its config when one was given).
[[nodiscard]] std::string MixedPixelsJson(const MixedPixelsOptions& options,
                                          const MixedPixelsResult& result);

/// Mixed pixels against Delta D drawn like the paper's Fig. 3, encoded as PNG bytes.
[[nodiscard]] std::vector<unsigned char> MixedPixelsPng(const MixedPixelsOptions& options,
                                                        const MixedPixelsResult& result);

}  // namespace casmap::pipeline
