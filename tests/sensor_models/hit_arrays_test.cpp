// FormReturn from the simulator's parallel hit arrays must equal FormReturn from the
// equivalent SubrayHit list bit for bit (the simulator uses the first, tests and CastPulse the
// second).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "casmap/sensor_models/lms200_model.hpp"

namespace casmap::sensor_models {
namespace {

struct Arrays {
    std::vector<float> distance_m, cos_incidence, reflectivity;
    std::vector<std::uint8_t> retro;
    std::vector<std::uint32_t> id;
    std::vector<SubrayHit> list;  // the same hits as SubrayHit (double of each float)

    [[nodiscard]] SubrayHitArrays View() const {
        return {distance_m.data(), cos_incidence.data(), reflectivity.data(), retro.data(),
                id.data(),         distance_m.size()};
    }
};

// A random pulse: a mix of misses, one or two surfaces a few cm or metres apart, grazing and
// head-on incidence, dark, bright and retro-reflective materials, some ranges beyond 100 m.
Arrays RandomPulse(std::mt19937_64& gen, std::size_t n) {
    std::uniform_real_distribution<float> u(0.0F, 1.0F);
    Arrays a;
    const float near = 0.1F + 30.0F * u(gen);
    const float far = near + (u(gen) < 0.5F ? 0.05F * u(gen) : 5.0F * u(gen));
    for (std::size_t i = 0; i < n; ++i) {
        const float pick = u(gen);
        float d = std::numeric_limits<float>::infinity();
        if (pick < 0.45F) {
            d = near + 0.01F * u(gen);
        } else if (pick < 0.85F) {
            d = far + 0.01F * u(gen);
        } else if (pick < 0.9F) {
            d = 150.0F;  // beyond max_trace_range_m
        }
        const float c = u(gen) < 0.1F ? 1.2F * u(gen) - 0.1F : u(gen);  // some outside 0..1
        const float rho = u(gen) < 0.2F ? 0.02F * u(gen) : u(gen);
        const bool retro = u(gen) < 0.05F;
        const auto id = static_cast<std::uint32_t>(gen() % 300);  // beyond the bias table too
        a.distance_m.push_back(d);
        a.cos_incidence.push_back(c);
        a.reflectivity.push_back(rho);
        a.retro.push_back(retro ? 1 : 0);
        a.id.push_back(id);
        SubrayHit h;  // a miss keeps the defaults, as the simulator's conversion did
        if (std::isfinite(d)) {
            h = SubrayHit{static_cast<double>(d), static_cast<double>(c), static_cast<double>(rho),
                          id, retro};
        }
        a.list.push_back(h);
    }
    return a;
}

void ExpectSame(const PulseResult& x, const PulseResult& y) {
    EXPECT_EQ(x.beam.raw, y.beam.raw);
    EXPECT_EQ(x.beam.status, y.beam.status);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(x.beam.range_m),
              std::bit_cast<std::uint32_t>(y.beam.range_m));
    EXPECT_EQ(x.label, y.label);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(x.true_range_m),
              std::bit_cast<std::uint32_t>(y.true_range_m));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(x.echo_range_m),
              std::bit_cast<std::uint64_t>(y.echo_range_m));
}

TEST(SubrayHitArrays, FormReturnMatchesTheHitListBitForBit) {
    std::mt19937_64 gen(5);
    for (const int subrays : {7, 19, 37}) {
        for (const bool ideal : {false, true}) {
            Lms200Config config;
            config.subrays_per_pulse = subrays;
            config.ideal = ideal;
            config.p_short = 0.02;  // exercise the spike paths too
            const Lms200Model model(config, 3);
            std::size_t valid = 0;
            for (std::uint32_t pulse = 0; pulse < 3000; ++pulse) {
                const Arrays a = RandomPulse(gen, model.SubrayCount());
                PulseContext context;
                context.scan_index = pulse / 181;
                context.beam = pulse % 181;
                const PulseResult from_list = model.FormReturn(context, a.list);
                const PulseResult from_arrays = model.FormReturn(context, a.View());
                ExpectSame(from_list, from_arrays);
                valid += from_list.beam.status == core::BeamStatus::kOk ? 1 : 0;
            }
            EXPECT_GT(valid, 500U) << "subrays " << subrays;  // the comparison saw ranges
        }
    }
}

}  // namespace
}  // namespace casmap::sensor_models
