#include "casmap/mapper/filter_params.hpp"

#include <gtest/gtest.h>

#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

std::string SetError(const std::string& assignment) {
    FilterParams p;
    try {
        p.SetAssignment(assignment);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(FilterParams, DefaultsAreValid) {
    EXPECT_NO_THROW(FilterParams{}.Validate());
    const FilterParams p;
    EXPECT_EQ(p.cas.k, 2);
    EXPECT_EQ(p.cas.h_sum_min, 7.0);
    EXPECT_FALSE(p.cas.e_term);
    EXPECT_EQ(p.baseline.window, 5);
}

TEST(FilterParams, SetsEveryNamedParameter) {
    FilterParams p;
    p.SetAssignment("A=9");
    p.Set("G", "80");
    p.Set("gs_mode", "variance");
    p.Set("normalise", "global");
    p.Set("e_term", "on");
    p.Set("E", "0.05");
    p.Set("B", "0.1");
    p.Set("h_sum_min", "6.5");
    p.Set("wm_empty", "skip");
    p.Set("noise", "0.0004");
    p.Set("center_weight", "5");
    p.Set("window", "7");
    p.Set("speed_m_s", "0.5");
    p.Set("edge_min", "9");
    p.Set("edge_tol_m", "0.04");
    EXPECT_EQ(p.cas.A, 9.0);
    EXPECT_EQ(p.cas.G, 80.0);
    EXPECT_EQ(p.cas.gs_mode, GsMode::kVariance);
    EXPECT_EQ(p.cas.normalise, Normalise::kGlobal);
    EXPECT_TRUE(p.cas.e_term);
    EXPECT_EQ(p.cas.E, 0.05);
    EXPECT_EQ(p.cas.B, 0.1);
    EXPECT_EQ(p.cas.h_sum_min, 6.5);
    EXPECT_EQ(p.cas.wm_empty, WmEmpty::kSkip);
    EXPECT_EQ(p.baseline.noise, 0.0004);
    EXPECT_EQ(p.baseline.center_weight, 5);
    EXPECT_EQ(p.baseline.window, 7);
    EXPECT_EQ(p.cas.speed_m_s, 0.5);
    EXPECT_EQ(p.cas.edge_min, 9);
    EXPECT_EQ(p.cas.edge_tol_m, 0.04);
    p.Set("sweep_jump.jump_min_m", "0.2");
    p.Set("sweep_jump.margin_m", "0.1");
    p.Set("sweep_jump.max_angle_deg", "7.5");
    p.Set("sweep_jump.reach", "2");
    EXPECT_EQ(p.sweep_jump.jump_min_m, 0.2);
    EXPECT_EQ(p.sweep_jump.margin_m, 0.1);
    EXPECT_EQ(p.sweep_jump.max_angle_deg, 7.5);
    EXPECT_EQ(p.sweep_jump.reach, 2);
    p.Set("edge_spill_c", "6");
    p.Set("edge_spill_drop_m", "0.02");
    p.Set("edge_spill", "0.25");
    EXPECT_EQ(p.cas.edge_spill_c, 6.0);
    EXPECT_EQ(p.cas.edge_spill_drop_m, 0.02);
    EXPECT_EQ(p.cas.edge_spill, 0.25);
    p.Set("nan_median_mix", "0.5");
    EXPECT_EQ(p.cas.nan_median_mix, 0.5);
    p.Set("consensus.spread_m", "0.03");
    p.Set("consensus.min_hits", "4");
    EXPECT_EQ(p.consensus.spread_m, 0.03);
    EXPECT_EQ(p.consensus.min_hits, 4);
    EXPECT_NO_THROW(p.Validate());
    EXPECT_EQ(FilterParams::Names().size(), 57U);  // 36 filter + 21 mapping-stage names
}

TEST(FilterParams, SetsTheWaveTwoOptions) {
    FilterParams p;
    p.Set("unknown", "nan");
    p.Set("ground", "local");
    p.Set("ground_k", "3");
    p.Set("ground_quantile", "0.5");
    p.Set("support", "height");
    p.Set("support_tol_m", "0.04");
    p.Set("support_min", "3");
    p.Set("surface_tol_m", "0.03");
    p.Set("surface_min", "9");
    EXPECT_EQ(p.cas.unknown, Unknown::kNaN);
    EXPECT_EQ(p.baseline.unknown, Unknown::kNaN);
    EXPECT_EQ(p.cas.ground, Ground::kLocal);
    EXPECT_EQ(p.cas.ground_k, 3);
    EXPECT_EQ(p.cas.ground_quantile, 0.5);
    EXPECT_EQ(p.cas.support, Support::kHeight);
    EXPECT_EQ(p.cas.support_tol_m, 0.04);
    EXPECT_EQ(p.cas.support_min, 3);
    EXPECT_EQ(p.cas.surface_tol_m, 0.03);
    EXPECT_EQ(p.cas.surface_min, 9);
    EXPECT_NO_THROW(p.Validate());
    for (const char* bad : {"unknown=none", "ground=flat", "ground_k=0", "ground_quantile=1.5",
                            "support=yes", "support_tol_m=0", "support_min=0", "surface_tol_m=0",
                            "surface_min=0", "surface_min=226"}) {
        const std::string e = SetError(bad);
        const std::string name = std::string(bad).substr(0, std::string(bad).find('='));
        EXPECT_NE(e.find(name), std::string::npos) << bad << ": " << e;
        EXPECT_NE(e.find("allowed"), std::string::npos) << bad << ": " << e;
    }
    EXPECT_EQ(ParseFilterMethod("cas_terrain"), FilterMethod::kCasTerrain);
    EXPECT_EQ(ParseFilterMethod("cas_trail"), FilterMethod::kCasTrail);
    EXPECT_EQ(AllFilterMethods().size(), 5U);  // the paper's benchmark columns stay five
}

TEST(FilterParams, RejectsUnknownName) {
    const std::string e = SetError("bogus=1");
    EXPECT_EQ(e.rfind("filter parameters: bogus = 1", 0), 0U) << e;  // the library names no flag
    EXPECT_NE(e.find("unknown filter parameter"), std::string::npos) << e;
}

TEST(FilterParams, RejectsOutOfRangeValues) {
    for (const char* bad : {"k=9", "k=0", "k=1.5", "window=4", "window=17", "center_weight=2",
                            "gs_mode=median", "noise=-1", "speed_m_s=0", "A=abc", "A=-1", "E=nan",
                            "normalise=max", "e_term=yes", "a=0"}) {
        const std::string e = SetError(bad);
        const std::string name = std::string(bad).substr(0, std::string(bad).find('='));
        EXPECT_EQ(e.rfind("filter parameters: " + name + " = ", 0), 0U) << bad << ": " << e;
        EXPECT_EQ(e.find("--"), std::string::npos) << bad << ": " << e;
        EXPECT_TRUE(e.find("(allowed: ") != std::string::npos ||
                    e.find("(must be a finite number)") != std::string::npos)
            << bad << ": " << e;
    }
    EXPECT_NE(SetError("k").find("NAME=VALUE"), std::string::npos);
}

// The mapping stages' parameters (scan pre-filters, Kalman mapper) are set by the same names
// everywhere (--set, presets, sweep axes); a bad value names the parameter and the rule.
TEST(FilterParams, SetsThePreFilterAndKalmanParameters) {
    FilterParams p;
    p.Set("shadow.min_angle_deg", "6");
    p.Set("shadow.max_angle_deg", "174");
    p.Set("shadow.window", "2");
    p.Set("shadow.neighbors", "0");
    p.Set("shadow.remove_start_point", "on");
    p.Set("range_jump.jump_min_m", "0.2");
    p.Set("range_jump.margin_m", "0.05");
    p.Set("range_jump.chord_tol_m", "0");
    p.Set("kalman.range_sigma_m", "0.01");
    p.Set("kalman.beam_constant_m", "0.001");
    p.Set("kalman.beam_angle_rad", "0.003");
    p.Set("kalman.min_variance_m2", "4e-6");
    p.Set("kalman.mahalanobis_gate", "3");
    p.Set("kalman.multi_height_noise_m2", "0");
    EXPECT_EQ(p.shadow.min_angle_deg, 6.0);
    EXPECT_EQ(p.shadow.max_angle_deg, 174.0);
    EXPECT_EQ(p.shadow.window, 2);
    EXPECT_EQ(p.shadow.neighbors, 0);
    EXPECT_TRUE(p.shadow.remove_start_point);
    EXPECT_EQ(p.range_jump.jump_min_m, 0.2);
    EXPECT_EQ(p.range_jump.margin_m, 0.05);
    EXPECT_EQ(p.range_jump.chord_tol_m, 0.0);
    EXPECT_EQ(p.kalman.range_sigma_m, 0.01);
    EXPECT_EQ(p.kalman.beam_constant_m, 0.001);
    EXPECT_EQ(p.kalman.beam_angle_rad, 0.003);
    EXPECT_EQ(p.kalman.min_variance_m2, 4e-6);
    EXPECT_EQ(p.kalman.mahalanobis_gate, 3.0);
    EXPECT_EQ(p.kalman.multi_height_noise_m2, 0.0);
    EXPECT_NO_THROW(p.Validate());
    // Defaults are the configs' own (laser_filters' example, the LMS 200 noise model).
    const FilterParams d;
    EXPECT_EQ(d.shadow.min_angle_deg, ShadowFilterConfig{}.min_angle_deg);
    EXPECT_EQ(d.range_jump.jump_min_m, RangeJumpConfig{}.jump_min_m);
    EXPECT_EQ(d.kalman.mahalanobis_gate, KalmanNoiseConfig{}.mahalanobis_gate);
    for (const char* bad :
         {"shadow.min_angle_deg=0", "shadow.min_angle_deg=90", "shadow.max_angle_deg=90",
          "shadow.max_angle_deg=180", "shadow.window=0", "shadow.window=11", "shadow.neighbors=-1",
          "shadow.window=1.5", "shadow.remove_start_point=yes", "range_jump.jump_min_m=0",
          "range_jump.margin_m=-0.01", "range_jump.chord_tol_m=x", "kalman.range_sigma_m=-1",
          "kalman.min_variance_m2=0", "kalman.mahalanobis_gate=0", "kalman.beam_angle_rad=inf",
          "sweep_jump.reach=0", "sweep_jump.reach=4", "sweep_jump.reach=1.5"}) {
        const std::string name = std::string(bad).substr(0, std::string(bad).find('='));
        FilterParams q;
        try {
            q.SetAssignment(bad);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), name) << bad << ": " << e.what();
            EXPECT_TRUE(e.rule().find("allowed: ") == 0 || e.rule() == "must be a finite number")
                << bad << ": " << e.rule();
        }
    }
}

// Cross-field rules are Validate's, so the order of the assignments does not matter.
TEST(FilterParams, CrossFieldRulesAreCheckedAfterEverySet) {
    FilterParams p;
    p.Set("range_jump.jump_min_m", "0.05");  // default margin 0.03 >= 0.05 / 2: not yet valid
    try {
        p.Validate();
        ADD_FAILURE() << "accepted margin 0.03 with jump_min_m 0.05";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "range_jump.margin_m") << e.what();
        EXPECT_NE(e.rule().find("jump_min_m / 2"), std::string::npos) << e.what();
    }
    p.Set("range_jump.margin_m", "0.02");
    EXPECT_NO_THROW(p.Validate());
}

TEST(FilterMethod, ParsesTheFiveNames) {
    EXPECT_EQ(ParseFilterMethod("cas"), FilterMethod::kCas);
    EXPECT_EQ(ParseFilterMethod("wiener"), FilterMethod::kWiener);
    EXPECT_EQ(ParseFilterMethod("average"), FilterMethod::kAverage);
    EXPECT_EQ(ParseFilterMethod("median"), FilterMethod::kMedian);
    EXPECT_EQ(ParseFilterMethod("cwm"), FilterMethod::kCwm);
    for (const FilterMethod m : AllFilterMethods()) {
        EXPECT_EQ(ParseFilterMethod(ToString(m)), m);
    }
    try {
        (void)ParseFilterMethod("gauss");
        FAIL() << "no throw";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("method = gauss (allowed: ", 0), 0U) << e.what();
    }
}

}  // namespace
}  // namespace casmap::mapper
