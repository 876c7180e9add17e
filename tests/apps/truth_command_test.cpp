// Runs the built `casmap truth` (simulator builds only; skipped when the command is absent).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Result {
    int status = -1;
    std::string output;  // stdout and stderr
};

Result RunCasmap(const std::string& args) {
    Result result;
    FILE* pipe = popen((std::string(CASMAP_EXE) + " " + args + " 2>&1").c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    char buffer[512];
    while (fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        result.output += buffer;
    }
    const int raw = pclose(pipe);
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return result;
}

class TruthCommand : public ::testing::Test {
protected:
    void SetUp() override {
        if (RunCasmap("truth --help").status != 0) {
            GTEST_SKIP() << "casmap built without the simulator";
        }
        dir_ = fs::temp_directory_path() / ("casmap_truth_" + std::to_string(getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

const std::string kCourse4 = std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course04.yaml";

TEST_F(TruthCommand, WritesAFloatTiffOfTheCourse) {
    const fs::path out = dir_ / "truth.tiff";
    const Result r =
        RunCasmap("truth --scene " + kCourse4 + " --grid 1.0,-1.0,0.025,200,80 --out " +
                  out.string() + " --threads 2");
    ASSERT_EQ(r.status, 0) << r.output;
    const cv::Mat map = cv::imread(out.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(map.type(), CV_32FC1);
    ASSERT_EQ(map.rows, 200);
    ASSERT_EQ(map.cols, 80);
    EXPECT_EQ(map.at<float>(40, 75), 0.914F);   // pole #1 at (2.0125, 0.8875)
    EXPECT_EQ(map.at<float>(80, 60), 0.414F);   // parallelepiped #2 at (3.0, 0.5)
    EXPECT_EQ(map.at<float>(168, 40), 0.459F);  // the cylinder at (5.2, 0.0)
    EXPECT_EQ(map.at<float>(10, 10), 0.0F);     // empty floor
}

TEST_F(TruthCommand, BadSceneExitsTwoWithOneLine) {
    const fs::path scene = dir_ / "bad.yaml";
    std::ofstream(scene) << "objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                            "    reflectivity: 1.4\n";
    const fs::path out = dir_ / "t.tiff";
    Result r = RunCasmap("truth --scene " + scene.string() +
                         " --grid 1.0,-1.0,0.025,200,80 --out " + out.string());
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.output, "casmap: " + scene.string() +
                            ":4:19: objects[0].reflectivity = 1.4 (allowed: 0..1)\n");
}

TEST_F(TruthCommand, BadGridOrOutputExitsTwo) {
    const fs::path out = dir_ / "t.tiff";
    Result r =
        RunCasmap("truth --scene " + kCourse4 + " --grid 1.0,-1.0,0.025,200 --out " + out.string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("--grid = 1.0,-1.0,0.025,200"), std::string::npos) << r.output;
    r = RunCasmap("truth --scene " + kCourse4 + " --grid 1.0,-1.0,0,200,80 --out " + out.string());
    EXPECT_EQ(r.status, 2) << r.output;
    r = RunCasmap("truth --scene " + kCourse4 + " --grid 1.0,-1.0,0.025,200,80 --out " +
                  (dir_ / "missing" / "t.tiff").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
