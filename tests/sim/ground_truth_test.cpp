#include "casmap/sim/ground_truth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/io/scene_file.hpp"

namespace casmap::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// The paper's map region as our courses place it: 200 rows along x from 1 m, 80 cols across y.
const core::GridGeometry kGrid{1.0, -1.0, 0.025, 200, 80};

core::SceneObject Object(const std::string& name,
                         core::Shape shape,
                         const Eigen::Vector3d& xyz,
                         const Eigen::Vector3d& rpy_deg = Eigen::Vector3d::Zero()) {
    core::SceneObject o;
    o.name = name;
    o.shape = std::move(shape);
    o.world_T_object = core::PoseFromXyzRpy(xyz, rpy_deg * kDeg);
    return o;
}

core::Scene FloorScene() {
    core::Scene scene;
    // Floor top exactly at z = 0 (centre -0.01, thickness 0.02).
    scene.objects.push_back(Object("floor", core::BoxShape{{14.0, 8.0, 0.02}}, {3.0, 0.0, -0.01}));
    return scene;
}

TEST(GroundTruth, EmptyFloorIsZero) {
    const core::MapF map = GroundTruthElevation(FloorScene(), kGrid, 1);
    ASSERT_EQ(map.rows, 200);
    ASSERT_EQ(map.cols, 80);
    for (const float z : map.data) {
        ASSERT_EQ(z, 0.0F);
    }
}

TEST(GroundTruth, BoxCellsCarryItsTopHeight) {
    core::Scene scene = FloorScene();
    const Eigen::Vector3d size(0.53, 0.559, 0.462);  // the paper's parallelepiped #1
    const Eigen::Vector3d centre(3.0, -0.5, 0.231);
    scene.objects.push_back(Object("box", core::BoxShape{size}, centre));
    const core::MapF map = GroundTruthElevation(scene, kGrid, 2);
    int box_cells = 0;
    for (int r = 0; r < kGrid.rows; ++r) {
        for (int c = 0; c < kGrid.cols; ++c) {
            // Oracle: the half-open cell overlaps the box footprint (no edge on a boundary).
            const double x_lo = kGrid.x0_m + r * kGrid.cell_m;
            const double y_lo = kGrid.y0_m + c * kGrid.cell_m;
            const bool overlaps = x_lo < centre.x() + size.x() / 2 &&
                                  x_lo + kGrid.cell_m > centre.x() - size.x() / 2 &&
                                  y_lo < centre.y() + size.y() / 2 &&
                                  y_lo + kGrid.cell_m > centre.y() - size.y() / 2;
            ASSERT_EQ(map.at(r, c), overlaps ? 0.462F : 0.0F) << r << "," << c;
            box_cells += overlaps ? 1 : 0;
        }
    }
    // x in [2.735, 3.265] spans rows 69..90 (22); y in [-0.7795, -0.2205] cols 8..31 (24).
    EXPECT_EQ(box_cells, 22 * 24);
}

TEST(GroundTruth, ThinPoleShowsInItsCell) {
    core::Scene scene = FloorScene();
    // Pole #9: 2.5 mm diameter, 914 mm long, centred in cell (40, 47).
    scene.objects.push_back(
        Object("pole9", core::CylinderShape{0.00125, 0.914}, {2.0125, 0.1875, 0.457}));
    // The same pole straddling the boundary x = 2.5 between rows 59 and 60.
    scene.objects.push_back(
        Object("pole9b", core::CylinderShape{0.00125, 0.914}, {2.5, -0.4875, 0.457}));
    const core::MapF map = GroundTruthElevation(scene, kGrid, 1);
    EXPECT_EQ(map.at(40, 47), 0.914F);
    EXPECT_EQ(map.at(59, 20), 0.914F);
    EXPECT_EQ(map.at(60, 20), 0.914F);
    int tall = 0;
    for (const float z : map.data) {
        tall += z > 0.0F ? 1 : 0;
    }
    EXPECT_EQ(tall, 3);
}

TEST(GroundTruth, CellCentreRuleMissesAPoleOffTheCentre) {
    core::Scene scene = FloorScene();
    scene.objects.push_back(
        Object("centred", core::CylinderShape{0.00125, 0.914}, {2.0125, 0.1875, 0.457}));
    scene.objects.push_back(
        Object("off", core::CylinderShape{0.00125, 0.914}, {2.0185, -0.1875, 0.457}));
    GroundTruthOptions centre;
    centre.rule = TruthRule::kCellCentre;
    const core::MapF c = GroundTruthElevation(scene, kGrid, centre, 1);
    const core::MapF any = GroundTruthElevation(scene, kGrid, 1);
    EXPECT_EQ(c.at(40, 47), 0.914F);
    EXPECT_EQ(any.at(40, 47), 0.914F);
    EXPECT_EQ(c.at(40, 32), 0.0F);  // 6 mm off the centre line
    EXPECT_EQ(any.at(40, 32), 0.914F);
}

TEST(GroundTruth, CellCentreRuleOnABox) {
    core::Scene scene = FloorScene();
    scene.objects.push_back(Object("box", core::BoxShape{{0.4, 0.343, 0.213}}, {4.1, 0.5, 0.1065}));
    GroundTruthOptions options;
    options.rule = TruthRule::kCellCentre;
    const core::MapF map = GroundTruthElevation(scene, kGrid, options, 2);
    for (int r = 0; r < kGrid.rows; ++r) {
        for (int c = 0; c < kGrid.cols; ++c) {
            const bool inside = std::abs(kGrid.CellCenterX(r) - 4.1) < 0.2 &&
                                std::abs(kGrid.CellCenterY(c) - 0.5) < 0.1715;
            ASSERT_EQ(map.at(r, c), inside ? 0.213F : 0.0F) << r << "," << c;
        }
    }
}

TEST(GroundTruth, TiltedBoxTopIsItsHighestCorner) {
    core::Scene scene = FloorScene();
    const core::Pose pose =
        core::PoseFromXyzRpy({3.0, 0.0, 0.5}, Eigen::Vector3d(8.0, -12.0, 20.0) * kDeg);
    scene.objects.push_back(Object("ramp", core::BoxShape{{1.2, 0.8, 0.05}}, {0, 0, 0}));
    scene.objects.back().world_T_object = pose;
    const core::MapF map = GroundTruthElevation(scene, kGrid, 2);
    // Cells well inside the top face: the plane's maximum over the four cell corners.
    const Eigen::Vector3d n = pose.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d p0 = pose * Eigen::Vector3d(0, 0, 0.025);
    int checked = 0;
    for (int r = 0; r < kGrid.rows; ++r) {
        for (int c = 0; c < kGrid.cols; ++c) {
            double top = -1e9;
            bool interior = true;
            for (const double dx : {0.0, kGrid.cell_m}) {
                for (const double dy : {0.0, kGrid.cell_m}) {
                    const double x = kGrid.x0_m + r * kGrid.cell_m + dx;
                    const double y = kGrid.y0_m + c * kGrid.cell_m + dy;
                    const double z = p0.z() - (n.x() * (x - p0.x()) + n.y() * (y - p0.y())) / n.z();
                    const Eigen::Vector3d local = pose.Inverse() * Eigen::Vector3d(x, y, z);
                    interior = interior && std::abs(local.x()) < 0.55 && std::abs(local.y()) < 0.35;
                    top = std::max(top, z);
                }
            }
            if (interior) {
                ASSERT_NEAR(map.at(r, c), top, 1e-6) << r << "," << c;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 300);
}

TEST(GroundTruth, LyingCylinderFollowsItsCircle) {
    core::Scene scene = FloorScene();
    // A log of radius 0.2 along world y (roll 90 deg), resting on the floor.
    scene.objects.push_back(
        Object("log", core::CylinderShape{0.2, 1.0}, {3.0125, 0.0, 0.2}, {90.0, 0.0, 0.0}));
    const core::MapF map = GroundTruthElevation(scene, kGrid, 1);
    const int c = 40;  // y in [0, 0.025): well inside the log's length
    // Row 80 holds the axis (x = 3.0125 is its centre): the top of the circle, 2 r.
    EXPECT_NEAR(map.at(80, c), 0.4, 1e-6);
    // Row 84 covers x in [3.1, 3.125): nearest point to the axis 0.0875 m off it.
    EXPECT_NEAR(map.at(84, c), 0.2 + std::sqrt(0.04 - 0.0875 * 0.0875), 1e-5);
    EXPECT_NEAR(map.at(76, c), 0.2 + std::sqrt(0.04 - 0.0875 * 0.0875), 1e-5);
    EXPECT_GT(map.at(72, c), 0.0F);  // x in [2.8, 2.825) touches the log (from x = 2.8125)
    EXPECT_EQ(map.at(71, c), 0.0F);  // x in [2.775, 2.8): beyond the radius
}

TEST(GroundTruth, DatumClampAndBelowDatum) {
    core::Scene scene;
    scene.objects.push_back(Object("pit", core::BoxShape{{0.5, 0.5, 0.1}}, {2.0, 0.0, -0.15}));
    const core::MapF clamped = GroundTruthElevation(scene, kGrid, 1);
    EXPECT_EQ(clamped.at(40, 40), 0.0F);
    GroundTruthOptions keep;
    keep.clamp_to_datum = false;
    const core::MapF raw = GroundTruthElevation(scene, kGrid, keep, 1);
    EXPECT_NEAR(raw.at(40, 40), -0.1, 1e-7);
    EXPECT_EQ(raw.at(0, 0), 0.0F);  // nothing there: the datum
}

TEST(GroundTruth, TerrainScenesKeepGroundBelowTheDatumByDefault) {
    core::Scene scene;
    scene.objects.push_back(Object("hollow", core::BoxShape{{0.5, 0.5, 0.1}}, {2.0, 0.0, -0.15}));
    scene.objects.back().terrain = true;
    EXPECT_FALSE(ClampsToDatum(scene, {}));
    EXPECT_NEAR(GroundTruthElevation(scene, kGrid, 1).at(40, 40), -0.1, 1e-7);
    GroundTruthOptions clamp;
    clamp.clamp_to_datum = true;  // the paper's flat-floor setting, asked for explicitly
    EXPECT_EQ(GroundTruthElevation(scene, kGrid, clamp, 1).at(40, 40), 0.0F);
    scene.objects.back().terrain = false;  // no terrain object: a course, clamped
    EXPECT_TRUE(ClampsToDatum(scene, {}));
}

TEST(GroundTruth, SameResultAtAnyThreadCount) {
    const core::Scene scene =
        io::LoadScene(std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course08.yaml");
    const core::MapF one = GroundTruthElevation(scene, kGrid, 1);
    const core::MapF two = GroundTruthElevation(scene, kGrid, 2);
    EXPECT_EQ(one.data, two.data);
}

TEST(GroundTruth, CourseFourShowsEveryObject) {
    const core::Scene scene =
        io::LoadScene(std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course04.yaml");
    const core::MapF map = GroundTruthElevation(scene, kGrid, 2);
    for (const core::SceneObject& o : scene.objects) {
        if (o.name == "floor") {
            continue;
        }
        const auto cell =
            kGrid.CellOf(o.world_T_object.translation.x(), o.world_T_object.translation.y());
        ASSERT_TRUE(cell.has_value()) << o.name << " outside the map region";
        const double top = o.world_T_object.translation.z() +
                           (std::holds_alternative<core::BoxShape>(o.shape)
                                ? std::get<core::BoxShape>(o.shape).size_m.z() / 2
                                : std::get<core::CylinderShape>(o.shape).height_m / 2);
        EXPECT_NEAR(map.at(cell->row, cell->col), top, 1e-6) << o.name;
    }
    EXPECT_EQ(map.at(0, 0), 0.0F);
}

TEST(GroundTruth, RejectsBadOptionsAndGrids) {
    GroundTruthOptions options;
    options.cylinder_segments = 3;
    EXPECT_THROW((void)GroundTruthElevation(FloorScene(), kGrid, options, 1), InputError);
    EXPECT_THROW((void)GroundTruthElevation(FloorScene(), core::GridGeometry{0, 0, 0.025, 0, 5}, 1),
                 InputError);
}

}  // namespace
}  // namespace casmap::sim
