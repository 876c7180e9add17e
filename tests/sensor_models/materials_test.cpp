// Retro-reflective and dark materials against closed forms (docs/sensor-model.md
// "Retro-reflectors and dark surfaces"): a full footprint on a plane normal to the beam at range
// r returns E = rho g R10^2 / (rho10 r^2) (units of the threshold T; g = retro_gain for a
// retro-reflector, else 1), so a retro-reflector saturates within
// r_sat = sqrt(rho g R10^2 / (rho10 saturation_peak)) and a dark surface is detected out to
// R = R10 sqrt(rho / rho10).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/sensor_models/lms200_model.hpp"

namespace casmap::sensor_models {
namespace {

constexpr std::size_t kFront = 90;  // beam 90 of the 1 deg / 180 deg scan looks along +x

// Every sub-ray of pulse (scan, kFront) on the plane x = range_m (normal to the beam).
std::vector<SubrayHit> PlaneHits(
    const Lms200Model& model, std::uint64_t scan, double range_m, double reflectivity, bool retro) {
    std::vector<Subray> rays(model.SubrayCount());
    model.PulseSubrays(scan, kFront, rays);
    std::vector<SubrayHit> hits(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Eigen::Vector3d& o = rays[i].origin;
        const Eigen::Vector3d& d = rays[i].direction;
        hits[i].distance_m = (range_m - o.x()) / d.x();
        hits[i].cos_incidence = d.x();
        hits[i].reflectivity = reflectivity;
        hits[i].surface_id = 1;
        hits[i].retro_reflective = retro;
    }
    return hits;
}

PulseResult Fire(const Lms200Model& m, std::uint64_t scan, double r, double rho, bool retro) {
    PulseContext p;
    p.scan_index = scan;
    p.beam = kFront;
    return m.FormReturn(p, PlaneHits(m, scan, r, rho, retro));
}

// Only the physics under test: no random artifacts, hard threshold.
Lms200Config Clean() {
    Lms200Config c;
    c.spikes_enabled = false;
    c.dropout_enabled = false;
    c.soft_threshold = false;
    return c;
}

double SaturationRangeM(const Lms200Config& c, double rho) {
    return std::sqrt(rho * c.retro_gain * c.r10_m * c.r10_m /
                     (c.r10_reflectivity * c.saturation_peak));
}

double DetectionRangeM(const Lms200Config& c, double rho) {
    return c.r10_m * std::sqrt(rho / c.r10_reflectivity);
}

TEST(Materials, RetroReflectorWithinSaturationRangeDazzles) {
    const Lms200Config c = Clean();
    const Lms200Model m{c, 3};
    for (const double rho : {1.0, 0.5}) {
        const double r_sat = SaturationRangeM(c, rho);  // 3.16 m for a new reflector
        ASSERT_GT(r_sat, 1.0);
        for (std::uint64_t scan = 0; scan < 20; ++scan) {
            const PulseResult in = Fire(m, scan, 0.95 * r_sat, rho, true);
            EXPECT_EQ(in.beam.status, core::BeamStatus::kDazzle) << rho << " " << scan;
            EXPECT_EQ(in.beam.raw, c.format.CodeFor(core::BeamStatus::kDazzle));
            EXPECT_EQ(in.beam.raw, 8190);  // the 8 m mm mode's dazzle code
            EXPECT_EQ(in.label, core::BeamLabel::kDazzled);
            // Beyond r_sat the reflector is a strong, valid target.
            const double r = 1.05 * r_sat;
            const PulseResult out = Fire(m, scan, r, rho, true);
            ASSERT_EQ(out.beam.status, core::BeamStatus::kOk) << rho << " " << scan;
            EXPECT_NEAR(out.beam.range_m, r, 0.04);  // bias <= 15 mm + noise sigma 5 mm
            EXPECT_EQ(out.label, core::BeamLabel::kValid);
        }
    }
}

TEST(Materials, DiffuseSurfacesNeverSaturate) {
    const Lms200Config c = Clean();
    const Lms200Model m{c, 3};
    // A white diffuser just beyond the minimum range peaks at R10^2 / (rho10 r^2) = 2.3e4 T.
    const double r = 1.05 * c.min_range_m;
    ASSERT_LT(c.r10_m * c.r10_m / (c.r10_reflectivity * r * r), c.saturation_peak);
    for (std::uint64_t scan = 0; scan < 20; ++scan) {
        const PulseResult white = Fire(m, scan, r, 1.0, false);
        EXPECT_EQ(white.beam.status, core::BeamStatus::kOk);
        EXPECT_EQ(white.label, core::BeamLabel::kValid);
        // The same surface as a retro-reflector saturates.
        EXPECT_EQ(Fire(m, scan, r, 1.0, true).label, core::BeamLabel::kDazzled);
    }
}

TEST(Materials, SaturationThresholdIsAConfigSetting) {
    Lms200Config c = Clean();
    c.saturation_peak = 1e12;  // a receiver that never saturates
    const Lms200Model m{c, 3};
    const PulseResult r = Fire(m, 0, 1.0, 1.0, true);
    EXPECT_EQ(r.beam.status, core::BeamStatus::kOk);
    EXPECT_EQ(r.label, core::BeamLabel::kValid);
    c.retro_gain = 0.5;  // out of range: a retro-reflector returns at least a diffuser's echo
    EXPECT_THROW(c.Validate(), InputError);
    c.retro_gain = 1000.0;
    c.saturation_peak = 0.5;  // below the detection threshold
    EXPECT_THROW(c.Validate(), InputError);
}

TEST(Materials, BlackSurfaceBeyondItsDetectionRangeIsMissing) {
    const Lms200Config c = Clean();
    const Lms200Model m{c, 3};
    const double rho = 0.02;                       // black rubber
    const double range = DetectionRangeM(c, rho);  // 4.47 m
    for (std::uint64_t scan = 0; scan < 20; ++scan) {
        const PulseResult near = Fire(m, scan, 0.97 * range, rho, false);
        ASSERT_EQ(near.beam.status, core::BeamStatus::kOk) << scan;
        EXPECT_EQ(near.label, core::BeamLabel::kValid);
        // Just beyond: E = 0.94 T >= 0.5 T -> 8187 (S/N too small).
        const PulseResult weak = Fire(m, scan, 1.03 * range, rho, false);
        EXPECT_EQ(weak.beam.status, core::BeamStatus::kLowSignal) << scan;
        EXPECT_EQ(weak.beam.raw, 8187);
        EXPECT_EQ(weak.label, core::BeamLabel::kMissing);
        // Farther than sqrt(2) R: E < 0.5 T -> 8191 (no echo).
        const PulseResult lost = Fire(m, scan, 1.5 * range, rho, false);
        EXPECT_EQ(lost.beam.status, core::BeamStatus::kNoReturn) << scan;
        EXPECT_EQ(lost.beam.raw, 8191);
        EXPECT_EQ(lost.label, core::BeamLabel::kMissing);
        // A 10 % surface at the same range is still detected.
        EXPECT_EQ(Fire(m, scan, 1.5 * range, 0.1, false).beam.status, core::BeamStatus::kOk);
    }
}

TEST(Materials, SoftThresholdLosesDarkSurfacesWithTheLogisticProbability) {
    Lms200Config c = Clean();
    c.soft_threshold = true;
    const Lms200Model m{c, 11};
    const double rho = 0.04;
    const double range = DetectionRangeM(c, rho);  // 6.3 m
    for (const double f : {0.8, 1.0, 1.2}) {
        const double e = 1.0 / (f * f);  // E / T at f R
        const double p = 1.0 / (1.0 + std::exp(-10.0 * std::log10(e) / c.soft_edge_db));
        const int n = 4000;
        int detected = 0;
        for (int scan = 0; scan < n; ++scan) {
            const PulseResult r = Fire(m, static_cast<std::uint64_t>(scan), f * range, rho, false);
            detected += r.beam.status == core::BeamStatus::kOk ? 1 : 0;
            if (r.beam.status != core::BeamStatus::kOk) {
                EXPECT_EQ(r.label, core::BeamLabel::kMissing);
            }
        }
        const double sd = std::sqrt(p * (1.0 - p) / n);
        EXPECT_NEAR(static_cast<double>(detected) / n, p, 4.0 * sd + 0.005) << "at " << f << " R";
    }
}

}  // namespace
}  // namespace casmap::sensor_models
