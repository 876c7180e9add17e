#include "casmap/pipeline/bench_wire.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace casmap::pipeline {
namespace {

core::MapF Map(int rows, int cols, float first) {
    core::MapF m;
    m.rows = rows;
    m.cols = cols;
    for (int i = 0; i < rows * cols; ++i) {
        m.data.push_back(first + 0.1F * static_cast<float>(i));
    }
    m.data[1] = std::numeric_limits<float>::quiet_NaN();
    return m;
}

TEST(BenchWire, RoundTripIsExactNanIncluded) {
    BenchRunRecord a;
    a.run.course = 4;
    a.run.test = "TRP";
    a.run.seed = 0xFFFFFFFFFFFFFFFFULL;
    a.run.filters["cas"] = {0.123456789012345678, 0.01, 3, std::nan("")};
    a.run.filters["median"] = {1.5, 0.02, 0, 0.004};
    a.run.filters["kalman"] = {0.9, 0.03, 2, 0.005, 15000, 0.75, std::nan(""), 0.011};
    a.run.scene = "scenes/outdoor.yaml";
    a.run.unknown = "nan";
    a.run.cas_classes.all = {16000, 1.25, 2.5, 96.25};
    a.run.cas_classes.observed = {15000, 1.3, 2.6, 96.1};
    a.run.raw_rmse_m = 0.0314;
    a.run.raw_spikes = 7;
    a.run.scans = 450;
    a.run.poles = {"pole1", "pole9"};
    a.run.poles_kept["raw"] = {"pole1"};
    a.run.poles_kept["cas"] = {};
    a.name = "course04_TRP";
    a.config_yaml = "seed: 1\nbinary: \x01\x02\n";
    a.has_sheet = true;
    a.sheet.raw = Map(3, 4, 0.5F);
    a.sheet.certainty = Map(3, 4, 1.0F);
    a.sheet.truth = Map(3, 4, -0.2F);
    a.sheet.filtered["cas"] = Map(3, 4, 0.25F);
    const std::string bytes = EncodeBenchRun(a);
    const BenchRunRecord b = DecodeBenchRun(bytes);
    EXPECT_EQ(EncodeBenchRun(b), bytes);
    EXPECT_EQ(b.run.course, 4);
    EXPECT_EQ(b.run.seed, a.run.seed);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(b.run.filters.at("cas").pi),
              std::bit_cast<std::uint64_t>(a.run.filters.at("cas").pi));
    EXPECT_TRUE(std::isnan(b.run.filters.at("cas").fill_error_m));
    const FilterScore& k = b.run.filters.at("kalman");
    EXPECT_EQ(k.cells, 15000);
    EXPECT_EQ(k.coverage, 0.75);
    EXPECT_TRUE(std::isnan(k.edge_rmse_m));
    EXPECT_EQ(k.open_rmse_m, 0.011);
    EXPECT_EQ(b.run.scene, "scenes/outdoor.yaml");
    EXPECT_EQ(b.run.unknown, "nan");
    EXPECT_EQ(b.run.poles_kept.at("raw"), a.run.poles_kept.at("raw"));
    EXPECT_EQ(b.config_yaml, a.config_yaml);
    ASSERT_TRUE(b.has_sheet);
    EXPECT_EQ(b.sheet.filtered.at("cas").data.size(), 12U);
    EXPECT_TRUE(std::isnan(b.sheet.truth.data[1]));
    EXPECT_THROW((void)DecodeBenchRun(bytes.substr(0, bytes.size() - 3)), std::runtime_error);
}

}  // namespace
}  // namespace casmap::pipeline
