// The bad-input corpus (tests/data/bad_inputs/cases.tsv): every case must exit 2 with one
// short line that contains the expected text, naming the file or flag and the field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.hpp"

namespace casmap::test {
namespace {
namespace fs = std::filesystem;

struct Case {
    std::string name;
    std::string needs;
    std::string expected;
    std::string args;
};

const fs::path kDataDir = fs::path(CASMAP_SOURCE_DIR) / "tests/data/bad_inputs";

std::vector<Case> LoadCases() {
    std::vector<Case> cases;
    std::ifstream in(kDataDir / "cases.tsv");
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') {
            continue;
        }
        std::vector<std::string> cols;
        std::stringstream fields(line);
        for (std::string col; std::getline(fields, col, '\t');) {
            cols.push_back(col);
        }
        if (cols.size() == 4) {
            cases.push_back({cols[0], cols[1], cols[2], cols[3]});
        } else {
            cases.push_back({"malformed", "any", "4 tab-separated columns", line});
        }
    }
    return cases;
}

std::string Expand(std::string text, const fs::path& tmp) {
    const std::pair<std::string, std::string> vars[] = {
        {"{d}", kDataDir.string()}, {"{s}", CASMAP_SOURCE_DIR}, {"{t}", tmp.string()}};
    for (const auto& [key, value] : vars) {
        for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
            text.replace(at, key.size(), value);
            at += value.size();
        }
    }
    return text;
}

// Without the simulator "simulate" is no subcommand (and "--help" after it still succeeds).
bool HaveSimulator() { return Casmap("simulate").output.find("--scene") != std::string::npos; }

TEST(BadInputs, EveryCaseExitsTwoWithOneLineNamingTheField) {
    const std::vector<Case> cases = LoadCases();
    ASSERT_GE(cases.size(), 30U);
    const bool sim = HaveSimulator();
    int ran = 0;
    for (const Case& c : cases) {
        if (c.needs == "sim" && !sim) {
            continue;
        }
        const fs::path tmp = fs::path(testing::TempDir()) /
                             ("casmap_bad_" + std::to_string(getpid()) + "_" + c.name);
        fs::remove_all(tmp);
        fs::create_directories(tmp);
        const Result r = Casmap(Expand(c.args, tmp));
        ++ran;
        const std::string shown = r.output.substr(0, 300);
        EXPECT_EQ(r.code, 2) << c.name << ": " << shown;
        EXPECT_NE(r.output.find(Expand(c.expected, tmp)), std::string::npos)
            << c.name << ": expected '" << c.expected << "' in: " << shown;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.name << ": " << shown;
        EXPECT_LT(r.output.size(), 320U) << c.name << ": " << shown;
        EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << c.name;
        // Nothing written: a rejected command leaves its output folder as it was (empty).
        EXPECT_TRUE(fs::is_empty(tmp)) << c.name;
        fs::remove_all(tmp);
    }
    std::printf("bad inputs: %d cases run, each exited 2 with one line\n", ran);
}

}  // namespace
}  // namespace casmap::test
