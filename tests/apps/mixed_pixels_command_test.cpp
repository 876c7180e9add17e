// `casmap mixed-pixels`: the Fig. 3 experiment runs, mixes at a gap below the echo width and
#include "tests/temp_dir.hpp"
// not at 3 m, and writes its JSON and PNG.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/temp_dir.hpp"
namespace casmap {
#include "tests/temp_dir.hpp"
namespace {
#include "tests/temp_dir.hpp"
namespace fs = std::filesystem;
#include "tests/temp_dir.hpp"
int RunCasmap(const std::string& args, std::string& output) {
#include "tests/temp_dir.hpp"
    const std::string cmd = std::string(CASMAP_EXE) + " " + args + " 2>&1";
#include "tests/temp_dir.hpp"
    FILE* pipe = popen(cmd.c_str(), "r");
#include "tests/temp_dir.hpp"
    char buffer[4096];
#include "tests/temp_dir.hpp"
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
#include "tests/temp_dir.hpp"
        output += buffer;
#include "tests/temp_dir.hpp"
    }
#include "tests/temp_dir.hpp"
    const int status = pipe != nullptr ? pclose(pipe) : -1;
#include "tests/temp_dir.hpp"
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
#include "tests/temp_dir.hpp"
}
#include "tests/temp_dir.hpp"
TEST(MixedPixelsCommand, MixesBelowThePulseLengthNotAtThreeMetres) {
#include "tests/temp_dir.hpp"
    const casmap::test::TempDir dir("mixed_pixels_cmd");
#include "tests/temp_dir.hpp"
    const fs::path json = dir / "fig3.json";
#include "tests/temp_dir.hpp"
    const fs::path png = dir / "fig3.png";
#include "tests/temp_dir.hpp"
    std::string out;
#include "tests/temp_dir.hpp"
    const int code = RunCasmap(
#include "tests/temp_dir.hpp"
        "mixed-pixels --from 0.5 --to 3.0 --step 2.5 --readings 400 --seed 3"
#include "tests/temp_dir.hpp"
        " --json " +
#include "tests/temp_dir.hpp"
            json.string() + " --png " + png.string(),
#include "tests/temp_dir.hpp"
        out);
#include "tests/temp_dir.hpp"
    ASSERT_EQ(code, 0) << out;
#include "tests/temp_dir.hpp"
    std::ifstream in(json);
#include "tests/temp_dir.hpp"
    std::stringstream text;
#include "tests/temp_dir.hpp"
    text << in.rdbuf();
#include "tests/temp_dir.hpp"
    const std::string s = text.str();
#include "tests/temp_dir.hpp"
    const std::size_t at = s.find("\"mixed\": [");
#include "tests/temp_dir.hpp"
    ASSERT_NE(at, std::string::npos) << s;
#include "tests/temp_dir.hpp"
    int mixed_close = -1;
#include "tests/temp_dir.hpp"
    int mixed_far = -1;
#include "tests/temp_dir.hpp"
    ASSERT_EQ(std::sscanf(s.c_str() + at, "\"mixed\": [%d, %d]", &mixed_close, &mixed_far), 2) << s;
#include "tests/temp_dir.hpp"
    EXPECT_GT(mixed_close, 100);  // 0.5 m: most straddling readings are mixed
#include "tests/temp_dir.hpp"
    EXPECT_EQ(mixed_far, 0);  // 3 m: the echoes separate
#include "tests/temp_dir.hpp"
    EXPECT_GT(fs::file_size(png), 1000U);
#include "tests/temp_dir.hpp"
}
#include "tests/temp_dir.hpp"
TEST(MixedPixelsCommand, RejectsBadFlagsWithCodeTwo) {
#include "tests/temp_dir.hpp"
    std::string out;
#include "tests/temp_dir.hpp"
    EXPECT_EQ(RunCasmap("mixed-pixels --step 0", out), 2) << out;
#include "tests/temp_dir.hpp"
    EXPECT_NE(out.find("--step"), std::string::npos) << out;
#include "tests/temp_dir.hpp"
}
#include "tests/temp_dir.hpp"
}  // namespace
#include "tests/temp_dir.hpp"
}  // namespace casmap
#include "tests/temp_dir.hpp"
