// `casmap mixed-pixels`: the Fig. 3 experiment runs, mixes at a gap below the echo width and
// not at 3 m, and writes its JSON and PNG.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace casmap {
namespace {
namespace fs = std::filesystem;

int RunCasmap(const std::string& args, std::string& output) {
    const std::string cmd = std::string(CASMAP_EXE) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    char buffer[4096];
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        output += buffer;
    }
    const int status = pipe != nullptr ? pclose(pipe) : -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(MixedPixelsCommand, MixesBelowThePulseLengthNotAtThreeMetres) {
    const fs::path dir = fs::path(testing::TempDir()) / "casmap_mixed_pixels_cmd";
    fs::create_directories(dir);
    const fs::path json = dir / "fig3.json";
    const fs::path png = dir / "fig3.png";
    fs::remove(json);
    fs::remove(png);
    std::string out;
    const int code = RunCasmap(
        "mixed-pixels --from 0.5 --to 3.0 --step 2.5 --readings 400 --seed 3"
        " --json " +
            json.string() + " --png " + png.string(),
        out);
    ASSERT_EQ(code, 0) << out;
    std::ifstream in(json);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    const std::size_t at = s.find("\"mixed\": [");
    ASSERT_NE(at, std::string::npos) << s;
    int mixed_close = -1;
    int mixed_far = -1;
    ASSERT_EQ(std::sscanf(s.c_str() + at, "\"mixed\": [%d, %d]", &mixed_close, &mixed_far), 2) << s;
    EXPECT_GT(mixed_close, 100);  // 0.5 m: most straddling readings are mixed
    EXPECT_EQ(mixed_far, 0);      // 3 m: the echoes separate
    EXPECT_GT(fs::file_size(png), 1000U);
}

TEST(MixedPixelsCommand, RejectsBadFlagsWithCodeTwo) {
    std::string out;
    EXPECT_EQ(RunCasmap("mixed-pixels --step 0", out), 2) << out;
    EXPECT_NE(out.find("--step"), std::string::npos) << out;
}

}  // namespace
}  // namespace casmap
