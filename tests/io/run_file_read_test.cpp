// io::ReadRunFile on files it must reject (each broken by h5py in one place: the error names
// the file and the dataset or attribute) and on a minimal file another tool wrote.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/run_file.hpp"
#include "run_file_fixtures.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
using test::kDeg;
using test::MakeRun;
using test::RunPython;
namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("run_file_" + name); }

void ExpectReadError(const fs::path& file, const std::string& needle) {
    try {
        (void)ReadRunFile(file);
        ADD_FAILURE() << "no error reading " << file;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
}

TEST(RunFile, ReaderRejectsBadFilesNamingFileAndDataset) {
    const fs::path dir = FreshDir("bad");
    ExpectReadError(dir / "missing.h5", "does not exist");
    std::ofstream(dir / "text.h5") << "not hdf5\n";
    ExpectReadError(dir / "text.h5", "not a readable HDF5 file");

    WriteRunFile(dir / "good.h5", MakeRun(3, 181));
    // Each case copies the good file and breaks one thing with h5py.
    int rc = 0;
    const std::string out = RunPython(dir, R"PY(
import h5py, numpy as np, shutil
d = ")PY" + dir.string() + R"PY("
def case(name, fn):
    shutil.copy(d + "/good.h5", d + "/" + name + ".h5")
    with h5py.File(d + "/" + name + ".h5", "r+") as f:
        fn(f)
def short_raw(f):
    del f["scans/raw"]; f["scans/raw"] = np.zeros((3, 180), np.uint16)
def float_status(f):
    del f["scans/status"]; f["scans/status"] = np.zeros((3, 181), np.float32)
def bad_status(f):
    f["scans/status"][1, 7] = 9
def bad_label(f):
    f["scans/labels"][0, 3] = 6
def no_angle(f):
    del f["scans"].attrs["angle_step_rad"]
def no_poses(f):
    del f["poses/quat_xyzw"]
def bad_quat(f):
    f["poses/quat_xyzw"][2] = [0, 0, 0, 2]
def backwards(f):
    f["poses/stamp_s"][3] = 0.0
def ok_nan(f):
    s = f["scans/status"][()]; r = f["scans/ranges_m"][()]
    i = np.argwhere(s == 0)[0]; r[i[0], i[1]] = np.nan; f["scans/ranges_m"][...] = r
def map_shape(f):
    del f["maps/certainty"]; f["maps/certainty"] = np.zeros((3, 4), np.float32)
def mode(f):
    f["scans"].attrs["range_mode"] = "80m"
for name, fn in list(globals().items()):
    if callable(fn) and name not in ("case",) and fn.__module__ == "__main__":
        case(name, fn)
print("ok")
)PY",
                                      &rc);
    ASSERT_EQ(rc, 0) << out;
    ExpectReadError(dir / "short_raw.h5", "/scans/raw");
    ExpectReadError(dir / "float_status.h5", "/scans/status = float");
    ExpectReadError(dir / "bad_status.h5", "/scans/status[1, 7] = 9");
    ExpectReadError(dir / "bad_label.h5", "/scans/labels[0, 3] = 6");
    ExpectReadError(dir / "no_angle.h5", "/scans attribute angle_step_rad");
    ExpectReadError(dir / "no_poses.h5", "/poses/quat_xyzw (required dataset is missing)");
    ExpectReadError(dir / "bad_quat.h5", "/poses/quat_xyzw[2]");
    ExpectReadError(dir / "backwards.h5", "/poses/stamp_s");
    ExpectReadError(dir / "ok_nan.h5", "/scans/ranges_m[");
    ExpectReadError(dir / "map_shape.h5", "/maps/certainty");
    ExpectReadError(dir / "mode.h5", "range_mode = 80m");
}

// A file made by another tool with only DESIGN.md's datasets and the scan-angle attributes
// (no casmap version, no maps, no labels) is a valid recorded run.
TEST(RunFile, ReadsAMinimalThirdPartyFile) {
    const fs::path dir = FreshDir("third_party");
    int rc = 0;
    const std::string out = RunPython(dir,
                                      R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "min.h5").string() +
                                          R"PY(", "w") as f:
    f["scans/stamp_s"] = np.array([0.0, 1 / 75])
    r = np.full((2, 181), 2.0, np.float32); r[1, 5] = np.nan
    f["scans/ranges_m"] = r
    f["scans/raw"] = np.full((2, 181), 2000, np.uint16)
    s = np.zeros((2, 181), np.uint8); s[1, 5] = 1
    f["scans/status"] = s
    f["scans"].attrs["start_angle_rad"] = -np.pi / 2
    f["scans"].attrs["angle_step_rad"] = np.pi / 180
    f["scans"].attrs["beam_period_s"] = 1 / 75 / 360
    f["poses/stamp_s"] = np.array([0.0, 1.0])
    f["poses/xyz_m"] = np.zeros((2, 3))
    f["poses/quat_xyzw"] = np.array([[0, 0, 0, 1.0], [0, 0, 0, 1.0]])
print("ok")
)PY",
                                      &rc);
    ASSERT_EQ(rc, 0) << out;
    const RunData run = ReadRunFile(dir / "min.h5");
    ASSERT_EQ(run.scans.size(), 2U);
    EXPECT_EQ(run.scans[1].beams[5].status, core::BeamStatus::kNoReturn);
    EXPECT_FLOAT_EQ(run.scans[1].beams[4].range_m, 2.0F);
    EXPECT_NEAR(run.scans[0].BeamAngle(180), 90 * kDeg, 1e-12);
    EXPECT_TRUE(run.truth.empty());
    EXPECT_EQ(run.poses.size(), 2U);
}

}  // namespace
}  // namespace casmap::io
