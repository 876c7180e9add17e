// mapper::StageSections: the one table every effective configuration renders the mapping
// stages' parameters from. It must list every stage parameter FilterParams::Set accepts, and
// its texts must read back through Set to the same values.
#include "casmap/mapper/stage_params.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace casmap::mapper {
namespace {

std::set<std::string> TableNames(const FilterParams& params) {
    std::set<std::string> names;
    for (const StageSection& section : StageSections(params)) {
        for (const StageParam& p : section.params) {
            names.insert(std::string(section.stage) + "." + p.key);
        }
    }
    return names;
}

// A field given a Set name but left out of the table (or the other way round) fails here.
TEST(StageSections, ListEveryStageParameterOfSet) {
    std::set<std::string> settable;
    for (const std::string& name : FilterParams::Names()) {
        if (name.find('.') != std::string::npos) {
            settable.insert(name);
        }
    }
    EXPECT_EQ(TableNames(FilterParams{}), settable);
}

TEST(StageSections, TextsReadBackThroughSet) {
    FilterParams set;
    for (const char* a :
         {"shadow.min_angle_deg=12.5", "shadow.window=3", "shadow.neighbors=2",
          "shadow.remove_start_point=on", "range_jump.chord_tol_m=0.0625",
          "sweep_jump.jump_min_m=0.3", "sweep_jump.margin_m=0.1", "sweep_jump.max_angle_deg=7.25",
          "sweep_jump.depression_share=0", "sweep_jump.reach=3", "kalman.min_variance_m2=2.5e-07",
          "kalman.mahalanobis_gate=0.1", "consensus.spread_m=0.035", "consensus.min_hits=5"}) {
        set.SetAssignment(a);
    }
    FilterParams back;
    for (const StageSection& section : StageSections(set)) {
        for (const StageParam& p : section.params) {
            back.Set(std::string(section.stage) + "." + p.key, p.value);
        }
    }
    const auto same = [](const FilterParams& a, const FilterParams& b) {
        return a.shadow.min_angle_deg == b.shadow.min_angle_deg &&
               a.shadow.max_angle_deg == b.shadow.max_angle_deg &&
               a.shadow.window == b.shadow.window && a.shadow.neighbors == b.shadow.neighbors &&
               a.shadow.remove_start_point == b.shadow.remove_start_point &&
               a.range_jump.jump_min_m == b.range_jump.jump_min_m &&
               a.range_jump.margin_m == b.range_jump.margin_m &&
               a.range_jump.chord_tol_m == b.range_jump.chord_tol_m &&
               a.sweep_jump.jump_min_m == b.sweep_jump.jump_min_m &&
               a.sweep_jump.margin_m == b.sweep_jump.margin_m &&
               a.sweep_jump.max_angle_deg == b.sweep_jump.max_angle_deg &&
               a.sweep_jump.depression_share == b.sweep_jump.depression_share &&
               a.sweep_jump.reach == b.sweep_jump.reach &&
               a.kalman.range_sigma_m == b.kalman.range_sigma_m &&
               a.kalman.beam_constant_m == b.kalman.beam_constant_m &&
               a.kalman.beam_angle_rad == b.kalman.beam_angle_rad &&
               a.kalman.min_variance_m2 == b.kalman.min_variance_m2 &&
               a.kalman.mahalanobis_gate == b.kalman.mahalanobis_gate &&
               a.kalman.multi_height_noise_m2 == b.kalman.multi_height_noise_m2 &&
               a.consensus.spread_m == b.consensus.spread_m &&
               a.consensus.min_hits == b.consensus.min_hits;
    };
    EXPECT_TRUE(same(back, set));
    EXPECT_FALSE(same(FilterParams{}, set));  // the settings above all reached the table
}

}  // namespace
}  // namespace casmap::mapper
