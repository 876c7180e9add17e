// pipeline::Record (what `casmap record` runs) called directly: the checks done before
// connecting name the options' fields, and a short recording from the virtual LMS 200 is
// reported and written.
#include "casmap/pipeline/record.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "../drivers/test_source.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/input_error_of.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

std::string FieldOfError(const RecordOptions& o) {
    return test::FieldOfError([&] { o.Validate(); });
}

TEST(Record, ChecksNameTheOptionsFields) {
    const casmap::test::TempDir tmp("pipeline_record_checks");
    const fs::path& dir = tmp.Path();
    RecordOptions o;
    o.device = "/nonexistent/lms";
    o.out = (dir / "run.h5").string();
    EXPECT_EQ(FieldOfError(o), "");
    o.out = "/nonexistent/run.h5";
    EXPECT_EQ(FieldOfError(o), "out");
    o.out = (dir / "run.h5").string();
    o.timeout_s = 0.0;
    EXPECT_EQ(FieldOfError(o), "timeout_s");
    o.timeout_s = 1.0;
    o.poses = "/nonexistent/poses.txt";
    EXPECT_EQ(FieldOfError(o), "poses");
    o.poses.clear();
    o.variant = "180,2";  // checked before connecting, by Record
    try {
        Record(o, {}, {});
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "variant");
    }
    EXPECT_FALSE(fs::exists(dir / "run.h5"));
}

// --mode's parameters are checked before connecting (the device here does not exist, so a
// check left to Connect would report the device instead), named as the "mode" field.
TEST(Record, ModeParametersAreCheckedBeforeConnecting) {
    const casmap::test::TempDir tmp("pipeline_record_mode");
    RecordOptions o;
    o.device = "/nonexistent/lms";
    o.out = (tmp.Path() / "run.h5").string();
    o.timeout_s = 0.05;
    const auto field_of_record = [&] {
        try {
            Record(o, {}, {});
        } catch (const InputError& e) {
            return e.field() + " = " + e.value();
        }
        return std::string("no error");
    };
    for (const char* mode : {"mean:1", "mean:251", "subrange:10-5", "subrange:0-5",
                             "subrange:1-402", "mean-subrange:300:1-5"}) {
        o.mode = mode;
        EXPECT_EQ(field_of_record(), "mode = " + std::string(mode));
    }
    o.variant = "100,1";  // 101 beams
    o.mode = "subrange:1-181";
    EXPECT_EQ(field_of_record(), "mode = subrange:1-181");
    o.mode = "subrange:1-101";  // fits: the device is the next problem
    EXPECT_EQ(field_of_record().rfind("mode", 0), std::string::npos);
    EXPECT_FALSE(fs::exists(tmp.Path() / "run.h5"));
}

TEST(Record, ReportsThenWritesWhatWasReceived) {
    const casmap::test::TempDir tmp("pipeline_record_run");
    const fs::path& dir = tmp.Path();
    drivers::testing::NumberedSource source;
    drivers::VirtualLms200Config vc;
    vc.link_path = "/tmp/casmap_pipeline_record_" + std::to_string(getpid());
    drivers::VirtualLms200 scanner(vc, source);
    scanner.Start();
    RecordOptions o;
    o.device = vc.link_path;
    o.out = (dir / "run.h5").string();
    o.scans = 3;
    o.timeout_s = 20.0;
    RecordStats stats;
    bool file_existed_at_report = true;
    Record(o, {}, [&](const RecordStats& s) {
        stats = s;
        file_existed_at_report = fs::exists(o.out);
    });
    scanner.Stop();
    EXPECT_EQ(stats.scans, 3U);
    EXPECT_GE(stats.connect_attempts, 1);
    EXPECT_GT(stats.counters.bytes, 0U);
    EXPECT_FALSE(file_existed_at_report);  // reported before the file is written
    const io::RunData run = io::ReadRunFile(o.out);
    EXPECT_EQ(run.scans.size(), 3U);
    EXPECT_NE(run.config_yaml.find("casmap record"), std::string::npos);
    // The reported rate is the written stamps' (it was the read times', which bunch up when
    // telegrams wait in the line's buffer: hundreds of "scans/s" from a 75 Hz scanner).
    const double span_s = run.scans.back().stamp_s - run.scans.front().stamp_s;
    ASSERT_GT(span_s, 0.0);
    EXPECT_DOUBLE_EQ(stats.scans_per_second, 2.0 / span_s);
}

}  // namespace
}  // namespace casmap::pipeline
