#include "casmap/sensor_models/lms200_config.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::sensor_models {
namespace {

// Expects Validate() to throw an InputError whose message names `field`.
void ExpectRejected(const std::function<void(Lms200Config&)>& mutate, const std::string& field) {
    Lms200Config config;
    mutate(config);
    try {
        config.Validate();
        FAIL() << "accepted an invalid " << field;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("lms200." + field), std::string::npos) << e.what();
    }
}

TEST(Lms200Config, DefaultsAreValid) { EXPECT_NO_THROW(Lms200Config{}.Validate()); }

TEST(Lms200Config, DefaultsFollowTheReferenceNote) {
    const Lms200Config c;
    EXPECT_EQ(c.angular_resolution_deg, 1.0);
    EXPECT_EQ(c.subrays_per_pulse, 19);
    EXPECT_DOUBLE_EQ(c.echo_width_m, 1.0);
    EXPECT_DOUBLE_EQ(c.r10_m, 10.0);
    EXPECT_DOUBLE_EQ(c.NoiseSigma0M(), 0.005);
    EXPECT_DOUBLE_EQ(c.MaterialBiasMaxM(), 0.015);
}

TEST(Lms200Config, RejectsUnknownResolution) {
    ExpectRejected([](Lms200Config& c) { c.angular_resolution_deg = 0.3; },
                   "angular_resolution_deg");
}

TEST(Lms200Config, RejectsQuarterDegreeOver180Degrees) {
    ExpectRejected([](Lms200Config& c) { c.angular_resolution_deg = 0.25; }, "field_of_view_deg");
    Lms200Config ok;
    ok.angular_resolution_deg = 0.25;
    ok.field_of_view_deg = 100.0;
    EXPECT_NO_THROW(ok.Validate());
}

TEST(Lms200Config, RejectsEachBadField) {
    ExpectRejected([](Lms200Config& c) { c.field_of_view_deg = 90.0; }, "field_of_view_deg");
    ExpectRejected([](Lms200Config& c) { c.subrays_per_pulse = 5; }, "subrays_per_pulse");
    ExpectRejected([](Lms200Config& c) { c.echo_width_m = 0.0; }, "echo_width_m");
    ExpectRejected([](Lms200Config& c) { c.lobe_bound_fraction = 1.0; }, "lobe_bound_fraction");
    ExpectRejected([](Lms200Config& c) { c.r10_reflectivity = 0.0; }, "r10_reflectivity");
    ExpectRejected([](Lms200Config& c) { c.p_dropout = -0.1; }, "p_dropout");
    ExpectRejected([](Lms200Config& c) { c.p_wrap = 1.5; }, "p_wrap");
    ExpectRejected([](Lms200Config& c) { c.noise_sigma0_mm_units_m = -1.0; },
                   "noise_sigma0_mm_units_m");
    ExpectRejected([](Lms200Config& c) { c.divergence_rad = 1.0; }, "divergence_rad");
    ExpectRejected([](Lms200Config& c) { c.sun_direction_world.setZero(); }, "sun_direction_world");
    ExpectRejected([](Lms200Config& c) { c.mixed_tolerance_m = 0.0; }, "mixed_tolerance_m");
}

}  // namespace
}  // namespace casmap::sensor_models
