// `casmap live --mapper paper|consensus --prefilter none|sweep_jump --set ...`: bad values exit
// 2 naming the flag or the parameter; in simulator builds a session with both stages writes
// them into config.yaml, counts the rejected beams, and rejects exactly the beams `casmap map`
// rejects with the same pre-filter over the run file the session recorded.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

std::string ReadText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The integer after "key": (JSON) or "key: " (YAML flow map) in `text`; -1 if absent.
long long NumberAfter(const std::string& text, const std::string& key) {
    for (const std::string& k : {"\"" + key + "\": ", key + ": "}) {
        const std::size_t at = text.find(k);
        if (at != std::string::npos) {
            return std::stoll(text.substr(at + k.size()));
        }
    }
    return -1;
}

TEST(LiveStagesCommand, BadStageSettingsExitTwoNamingTheField) {
    const test::TempDir dir("live_stages_cli");
    const std::string base =
        "live --device /dev/null --poses p.txt --out " + (dir / "out").string() + " ";
    const auto expect = [&](const std::string& flags, const std::string& names) {
        const Result r = Casmap(base + flags);
        EXPECT_EQ(r.code, 2) << flags << ": " << r.output;
        EXPECT_NE(r.output.find(names), std::string::npos) << flags << ": " << r.output;
    };
    expect("--mapper kalman", "--mapper = kalman");
    expect("--mapper nearest", "--mapper = nearest");
    expect("--prefilter range_jump", "--prefilter = range_jump");
    expect("--set sweep_jump.reach=2", "--set = sweep_jump.reach=2");            // pre-filter none
    expect("--set consensus.spread_m=0.03", "--set = consensus.spread_m=0.03");  // mapper paper
    expect("--prefilter sweep_jump --set sweep_jump.reach=4", "sweep_jump.reach = 4");
    expect("--prefilter sweep_jump --set sweep_jump.margin_m=0.2", "sweep_jump.margin_m");
    expect("--mapper consensus --set consensus.min_hits=1", "consensus.min_hits = 1");
    expect("--mapper consensus --set consensus.spread_m=x", "consensus.spread_m = x");
}

#ifdef CASMAP_TEST_WITH_SIM
TEST(LiveStagesCommand, RejectsTheBeamsCasmapMapRejects) {
    const test::TempDir dir("live_stages_sim");
    const fs::path out = dir / "live";
    const Result r = Casmap("live --scene " + std::string(CASMAP_SOURCE_DIR) +
                            "/scenes/courses/course04.yaml --motion T --mapper consensus "
                            "--prefilter sweep_jump --set consensus.spread_m=0.03 "
                            "--snapshot-every-s 0 --out " +
                            out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const long long rejected = NumberAfter(r.output, "beams_rejected");
    EXPECT_GT(rejected, 0) << r.output;  // the course's box edges make mixed pixels
    EXPECT_EQ(NumberAfter(ReadText(out / "status.json"), "beams_rejected"), rejected);
    const std::string config = ReadText(out / "config.yaml");
    EXPECT_NE(config.find("mode: consensus, prefilter: sweep_jump"), std::string::npos) << config;
    EXPECT_NE(config.find("consensus: {spread_m: 0.03, min_hits: 2}"), std::string::npos) << config;
    EXPECT_NE(config.find("sweep_jump: {jump_min_m: 0.1"), std::string::npos) << config;
    // Offline over what the session recorded: the same labels, so the same count.
    const Result map = Casmap("map " + (out / "run.h5").string() + " --out " +
                              (dir / "map").string() + " --prefilter sweep_jump");
    ASSERT_EQ(map.code, 0) << map.output;
    EXPECT_EQ(NumberAfter(ReadText(dir / "map" / "map.yaml"), "beams_rejected"), rejected);
}
#endif

}  // namespace
}  // namespace casmap
