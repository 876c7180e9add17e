// casmap.load_scene, scan_at, simulate, truth (simulator builds only): the scene as an Embree
// world, one LMS 200 scan at a pose, a whole rig run, the exact ground-truth map.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/scan_at.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/sim/ground_truth.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"
#include "convert.hpp"

namespace casmap::python {
namespace {

/// A loaded scene and its ray-casting world, built once and shared by every call.
struct LoadedScene {
    std::string path;
    core::Scene scene;
    std::unique_ptr<sim::World> world;
};

std::shared_ptr<LoadedScene> LoadSceneFile(const std::filesystem::path& path) {
    auto s = std::make_shared<LoadedScene>();
    py::gil_scoped_release release;
    s->path = path.string();
    s->scene = io::LoadScene(path);
    s->world = std::make_unique<sim::World>(s->scene);
    return s;
}

py::dict ScanAt(const LoadedScene& scene,
                const std::vector<double>& pose_values,
                std::uint64_t seed,
                const std::optional<std::string>& sensor,
                bool ideal) {
    const core::Pose pose = pipeline::PoseFromXyzRpyDeg(pose_values);  // as `casmap scan --pose`
    sim::ScanResult r;
    {
        py::gil_scoped_release release;
        const sensor_models::Lms200Config config =
            pipeline::MakeScanSensorConfig({sensor.value_or(""), ideal, {}, {}});
        const sensor_models::Lms200Model model(config, seed);
        r = sim::CastScanAt(*scene.world, model, pose, 0.0, 0);  // as `casmap scan`
    }
    const std::size_t n = r.scan.beams.size();
    py::array_t<double> angles(static_cast<py::ssize_t>(n));
    py::array_t<float> ranges(static_cast<py::ssize_t>(n));
    py::array_t<std::uint16_t> raw(static_cast<py::ssize_t>(n));
    py::array_t<std::uint8_t> status(static_cast<py::ssize_t>(n));
    py::array_t<std::uint8_t> labels(static_cast<py::ssize_t>(n));
    py::array_t<float> true_range(static_cast<py::ssize_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
        angles.mutable_at(i) = r.scan.BeamAngle(i);
        ranges.mutable_at(i) = r.scan.beams[i].range_m;
        raw.mutable_at(i) = r.scan.beams[i].raw;
        status.mutable_at(i) = static_cast<std::uint8_t>(r.scan.beams[i].status);
        labels.mutable_at(i) = static_cast<std::uint8_t>(r.truth.labels[i]);
        true_range.mutable_at(i) = r.truth.true_range_m[i];
    }
    py::dict d;
    d["angles_rad"] = angles;
    d["ranges_m"] = ranges;
    d["raw"] = raw;
    d["status"] = status;
    d["labels"] = labels;
    d["true_range_m"] = true_range;
    return d;
}

py::dict Simulate(const LoadedScene& scene,
                  const std::string& motion,
                  std::uint64_t seed,
                  const std::optional<std::string>& rig,
                  const std::optional<std::string>& sensor,
                  const std::optional<double>& speed_m_s,
                  int threads) {
    pipeline::SimulatedRun result;
    {
        py::gil_scoped_release release;
        pipeline::SimFlags flags;  // what `casmap simulate` resolves from its flags
        flags.scene_path = scene.path;
        flags.motion = motion;
        flags.seed = seed;
        flags.rig_path = rig.value_or("");
        flags.sensor_path = sensor.value_or("");
        flags.speed_m_s = speed_m_s;
        const pipeline::SimSetup setup = pipeline::ResolveSimSetup(flags);
        const core::Trajectory poses = pipeline::RigTrajectory(setup, scene.scene);
        pipeline::SimulateRunOptions options;
        options.threads = threads;
        result = pipeline::SimulateRun(setup, scene.scene, *scene.world, poses, options);
    }
    return RunToDict(result.run);
}

}  // namespace

void BindSim(py::module_& m) {
    py::class_<LoadedScene, std::shared_ptr<LoadedScene>>(
        m, "Scene", "A scene file (scenes/*.yaml) loaded with its meshes, ready to ray-cast.")
        .def_readonly("path", &LoadedScene::path)
        .def_property_readonly("object_names",
                               [](const LoadedScene& s) {
                                   std::vector<std::string> names;
                                   for (const core::SceneObject& o : s.scene.objects) {
                                       names.push_back(o.name);
                                   }
                                   return names;
                               })
        .def("__repr__", [](const LoadedScene& s) {
            return "casmap.Scene('" + s.path + "', " + std::to_string(s.scene.objects.size()) +
                   " objects)";
        });
    m.def("load_scene", &LoadSceneFile, py::arg("path"),
          "Loads a scene YAML file (and the meshes it names) and builds its ray-casting world.");
    m.def("_scan_at", &ScanAt);
    m.def("_simulate", &Simulate);
    m.def(
        "truth",
        [](const LoadedScene& scene, const core::GridGeometry& grid, int threads) {
            core::MapF truth;
            {
                py::gil_scoped_release release;
                truth = sim::GroundTruthElevation(scene.scene, grid, threads);
            }
            return FromMap(truth);
        },
        py::arg("scene"), py::arg("grid"), py::arg("threads") = 0,
        "The exact ground-truth elevation (m) of every cell of `grid`: the highest surface point "
        "in the cell (as `casmap truth`). Any thread count gives the same map.");
}

}  // namespace casmap::python
