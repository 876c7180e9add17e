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
    EXPECT_NO_THROW(p.Validate());
    EXPECT_EQ(FilterParams::Names().size(), 24U);
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
    EXPECT_EQ(p.cas.unknown, Unknown::kNaN);
    EXPECT_EQ(p.baseline.unknown, Unknown::kNaN);
    EXPECT_EQ(p.cas.ground, Ground::kLocal);
    EXPECT_EQ(p.cas.ground_k, 3);
    EXPECT_EQ(p.cas.ground_quantile, 0.5);
    EXPECT_EQ(p.cas.support, Support::kHeight);
    EXPECT_EQ(p.cas.support_tol_m, 0.04);
    EXPECT_EQ(p.cas.support_min, 3);
    EXPECT_NO_THROW(p.Validate());
    for (const char* bad : {"unknown=none", "ground=flat", "ground_k=0", "ground_quantile=1.5",
                            "support=yes", "support_tol_m=0", "support_min=0"}) {
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
    EXPECT_NE(e.find("--set"), std::string::npos) << e;
    EXPECT_NE(e.find("bogus"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown filter parameter"), std::string::npos) << e;
}

TEST(FilterParams, RejectsOutOfRangeValues) {
    for (const char* bad : {"k=9", "k=0", "k=1.5", "window=4", "window=17", "center_weight=2",
                            "gs_mode=median", "noise=-1", "speed_m_s=0", "A=abc", "A=-1", "E=nan",
                            "normalise=max", "e_term=yes", "a=0"}) {
        const std::string e = SetError(bad);
        const std::string name = std::string(bad).substr(0, std::string(bad).find('='));
        EXPECT_NE(e.find("--set: " + name + " = "), std::string::npos) << bad << ": " << e;
        EXPECT_TRUE(e.find("(allowed: ") != std::string::npos ||
                    e.find("(must be a finite number)") != std::string::npos)
            << bad << ": " << e;
    }
    EXPECT_NE(SetError("k").find("NAME=VALUE"), std::string::npos);
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
        EXPECT_NE(std::string(e.what()).find("--method = gauss"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace casmap::mapper
