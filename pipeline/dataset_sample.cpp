#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/rig_config.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/pipeline/dataset.hpp"
#include "casmap/pipeline/dataset_setup.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/sha256.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/scenegen/scene_writer.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/ground_truth.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// NaN/inf have no JSON number: null.
Json Number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json Vec3(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json DrawJson(const scenegen::DomainDraw& d) {
    Json rig = {{"motion", d.motion},
                {"speed_m_s", d.speed_m_s},
                {"mount_pitch_deg", d.mount_pitch_deg},
                {"lateral_offset_m", d.lateral_offset_m}};
    if (d.motion == "vehicle") {
        rig["vehicle_mount_height_m"] = d.vehicle_mount_height_m;
    } else {
        rig["sensor_height_m"] = d.sensor_height_m;
        rig["roll"] = {{"shape", d.roll_triangle ? "triangle" : "sinusoid"},
                       {"amplitude_deg", d.roll_amplitude_deg},
                       {"period_s", d.roll_period_s}};
        rig["pitch"] = {{"shape", d.pitch_triangle ? "triangle" : "sinusoid"},
                        {"center_deg", d.pitch_center_deg},
                        {"amplitude_deg", d.pitch_amplitude_deg},
                        {"period_s", d.pitch_period_s}};
    }
    return rig;
}

Json SensorJson(const scenegen::DomainDraw& d) {
    return {{"seed", d.sensor_seed},
            {"angular_resolution_deg", d.angular_resolution_deg},
            {"field_of_view_deg", d.field_of_view_deg},
            {"range_mode", d.range_mode},
            {"noise_sigma0_m", d.noise_sigma0_m},
            {"divergence_rad", d.divergence_rad},
            {"echo_width_m", d.echo_width_m},
            {"lobe_bound_fraction", d.lobe_bound_fraction},
            {"p_short", d.p_short},
            {"p_dropout", d.p_dropout}};
}

Json PoseErrorJson(const scenegen::DomainDraw& d) {
    if (!d.pose_error) {
        return {{"enabled", false}};
    }
    return {{"enabled", true},
            {"seed", d.pose_error_seed},
            {"position_bias_m", Vec3(d.position_bias_m)},
            {"attitude_bias_deg", Vec3(d.attitude_bias_deg)},
            {"position_jitter_m", d.position_jitter_m},
            {"attitude_jitter_deg", d.attitude_jitter_deg}};
}

Json SceneJson(const scenegen::GeneratedScene& s, std::size_t triangles) {
    std::array<int, scenegen::kObjectKinds> kinds{};
    double thinnest_pole = 0.0;
    for (const scenegen::GenObject& o : s.objects) {
        ++kinds[static_cast<std::size_t>(o.kind)];
        if (o.kind == scenegen::ObjectKind::kPole &&
            (thinnest_pole == 0.0 || 2.0 * o.radius_m < thinnest_pole)) {
            thinnest_pole = 2.0 * o.radius_m;
        }
    }
    Json k = Json::object();
    for (std::size_t i = 0; i < kinds.size(); ++i) {
        k[scenegen::ObjectKindName(static_cast<scenegen::ObjectKind>(i))] = kinds[i];
    }
    int holes = 0;
    for (const scenegen::NegativeObstacle& n : s.negatives) {
        holes += n.ditch ? 0 : 1;
    }
    const auto [lo, hi] = std::minmax_element(s.ground.z_m.begin(), s.ground.z_m.end());
    return {{"type", s.terrain ? "terrain" : "course"},
            {"objects", s.objects.size()},
            {"kinds", k},
            {"holes", holes},
            {"ditches", static_cast<int>(s.negatives.size()) - holes},
            {"thinnest_pole_m", thinnest_pole > 0.0 ? Json(thinnest_pole) : Json(nullptr)},
            {"ground_z_m", Json::array({*lo, *hi})},
            {"ground_reflectivity", s.ground_reflectivity},
            {"triangles", triangles},
            {"placement_failures", s.placement_failures}};
}

Json LabelCounts(const io::RunData& run) {
    std::array<std::int64_t, core::kBeamLabelCount> counts{};
    for (const core::ScanTruth& t : run.truth) {
        for (const core::BeamLabel l : t.labels) {
            ++counts[static_cast<std::size_t>(l)];
        }
    }
    Json j = Json::object();
    for (int i = 0; i < core::kBeamLabelCount; ++i) {
        j[std::string(core::ToString(static_cast<core::BeamLabel>(i)))] =
            counts[static_cast<std::size_t>(i)];
    }
    return j;
}

// Runs the five filters, scores them against the truth over the paper's region and stores
// their outputs in `maps` as the spec asks.
Json FilterAndScore(const scenegen::DatasetSpec& spec,
                    const SimSetup& setup,
                    const MappedRun& mapped,
                    io::RunMaps& maps) {
    mapper::FilterParams params;
    params.cas.cell_m = setup.grid.cell_m;
    params.cas.speed_m_s = setup.vehicle ? setup.vehicle_config.speed_m_s : setup.table.speed_m_s;
    params.cas.scan_period_s = sensor_models::Lms200Model(setup.lms).ScanPeriodS();
    params.cas.a = mapped.config.a;
    params.Validate();
    const core::MapF& raw = mapped.elevation;
    const mapper::Region region = mapper::PaperRegion(raw.rows, raw.cols);
    Json pi = Json::object();
    Json classes;
    for (const mapper::FilterMethod m : mapper::AllFilterMethods()) {
        const std::string name(mapper::ToString(m));
        mapper::FilterResult r = mapper::RunFilter(m, raw, mapped.certainty, params);
        pi[name] = Number(mapper::PerformanceIndex(r.elevation, raw, *maps.truth_m, region));
        if (m == mapper::FilterMethod::kCas) {
            const mapper::ClassReport rep = mapper::ClassPercentages(r.classes, mapped.certainty);
            classes = {{"removed_pct", Number(rep.all.removed_pct)},
                       {"filled_pct", Number(rep.all.filled_pct)},
                       {"untouched_pct", Number(rep.all.untouched_pct)}};
            if (spec.outputs.cas_classes) {
                maps.cas_classes = std::move(r.classes);
            }
        }
        if (spec.outputs.filtered) {
            maps.filtered[name] = std::move(r.elevation);
        }
    }
    return {{"pi", pi}, {"cas_classes", classes}};
}

std::vector<std::string> RockNames(const DatasetContext& context) {
    std::vector<std::string> names;
    for (const fs::path& p : context.rock_meshes) {
        names.push_back(p.filename().string());
    }
    return names;
}

// Writes the scene files; returns the file names written (relative to the sample directory).
std::vector<std::string> WriteScene(const DatasetContext& context,
                                    const scenegen::GeneratedScene& gs,
                                    std::size_t index,
                                    std::uint64_t scene_seed,
                                    const fs::path& dir) {
    std::vector<std::string> files = {"scene.yaml", "ground.ply"};
    const std::vector<std::string> rocks = RockNames(context);
    std::vector<bool> used(rocks.size(), false);
    for (const scenegen::GenObject& o : gs.objects) {
        if (o.kind == scenegen::ObjectKind::kRock) {
            used[static_cast<std::size_t>(o.rock_mesh)] = true;
        }
    }
    for (std::size_t r = 0; r < rocks.size(); ++r) {
        if (used[r]) {
            std::ifstream in(context.rock_meshes[r], std::ios::binary);
            std::stringstream bytes;
            bytes << in.rdbuf();
            io::WriteTextAtomically(dir / rocks[r], bytes.str());
            files.push_back(rocks[r]);
        }
    }
    io::WriteTextAtomically(dir / "ground.ply", scenegen::PlyBinary(scenegen::ToMesh(gs.ground)));
    const std::string comment = "casmap dataset sample " + std::to_string(index) + ", scene seed " +
                                std::to_string(scene_seed) +
                                " (generated by scenegen; the ground is ground.ply)";
    io::WriteTextAtomically(dir / "scene.yaml",
                            scenegen::SceneYaml(gs, "ground.ply", rocks, comment));
    return files;
}

// The simulation, mapping, filtering and files of one sample; throws on any failure.
Json Simulate(const scenegen::DatasetSpec& spec,
              const DatasetContext& context,
              std::size_t index,
              const fs::path& dir,
              Json& line) {
    const std::uint64_t seed = line["seed"].get<std::uint64_t>();
    scenegen::Rng rng(seed);
    const scenegen::DomainDraw draw = scenegen::DrawDomain(spec.domain, rng);
    const std::uint64_t scene_seed = rng.Next();
    const scenegen::GeneratedScene gs = scenegen::GenerateScene(
        SampleSceneConfig(spec, draw), scene_seed, static_cast<int>(context.rock_meshes.size()));
    line["rig"] = DrawJson(draw);
    line["sensor"] = SensorJson(draw);
    line["pose_error"] = PoseErrorJson(draw);
    // Start clean: a killed run may have left temporaries or files of an older spec here.
    std::error_code ec;
    fs::remove_all(dir, ec);
    io::EnsureDirectory(dir);
    std::vector<std::string> files = WriteScene(context, gs, index, scene_seed, dir);
    const core::Scene scene = io::LoadScene((dir / "scene.yaml").string());
    std::size_t triangles = 0;
    for (const core::SceneObject& o : scene.objects) {
        if (const auto* m = std::get_if<core::MeshShape>(&o.shape)) {
            triangles += m->triangles.size();
        }
    }
    line["scene"] = SceneJson(gs, triangles);
    line["scene"]["seed"] = scene_seed;
    const SimSetup setup = SampleSetup(spec, draw, "scene.yaml");
    io::WriteTextAtomically(
        dir / "rig.yaml",
        io::RigConfigToYaml({setup.table, setup.vehicle_config, setup.pose_error}));
    io::WriteTextAtomically(dir / "sensor.yaml", io::Lms200ConfigToYaml(setup.lms));
    files.insert(files.end(), {"rig.yaml", "sensor.yaml"});
    const sim::World world(scene);
    SimulateRunOptions sim_options;
    sim_options.threads = 1;
    sim_options.truth = false;
    SimulatedRun sim = SimulateRun(setup, scene, world, RigTrajectory(setup, scene), sim_options);
    io::RunData& run = sim.run;
    sim::GroundTruthOptions truth_options;
    truth_options.clamp_to_datum = false;  // holes and ditches keep their negative heights
    run.maps.truth_m = sim::GroundTruthElevation(scene, setup.grid, truth_options, 1);
    const MappedRun mapped = MapScans(run.scans, run.poses, setup.grid);
    run.maps.elevation_m = mapped.elevation;
    run.maps.certainty = mapped.certainty;
    const Json scores = FilterAndScore(spec, setup, mapped, run.maps);
    io::WriteRunFile(dir / "run.h5", run);
    files.push_back("run.h5");
    line["scans"] = run.scans.size();
    line["labels"] = LabelCounts(run);
    line["pi"] = scores["pi"];
    line["cas_classes"] = scores["cas_classes"];
    line["simulate"] = "casmap simulate --scene scene.yaml --motion " + draw.motion +
                       " --rig rig.yaml --sensor sensor.yaml --seed " +
                       std::to_string(draw.sensor_seed) + " --out again.h5";
    Json list = Json::array();
    std::string sums;
    for (const std::string& f : files) {
        const std::string hex = Sha256File(dir / f);
        list.push_back({{"path", f}, {"bytes", fs::file_size(dir / f)}, {"sha256", hex}});
        sums += hex + "  " + f + "\n";
    }
    io::WriteTextAtomically(dir / "files.sha256", sums);
    return list;
}

std::string SampleDirName(std::size_t index) {
    std::string digits = std::to_string(index);
    return std::string(digits.size() < 6 ? 6 - digits.size() : 0, '0') + digits;
}

}  // namespace

fs::path SampleDir(const fs::path& out_dir, std::size_t index) {
    return out_dir / "samples" / SampleDirName(index);
}

SampleRecord GenerateSample(const scenegen::DatasetSpec& spec,
                            const DatasetContext& context,
                            std::size_t index) {
    const fs::path dir = SampleDir(context.out_dir, index);
    const std::uint64_t seed = scenegen::SampleSeed(spec.seed, index);
    Json line = {{"index", index},
                 {"seed", seed},
                 {"split", scenegen::SplitOf(spec, seed)},
                 {"status", "ok"},
                 {"dir", "samples/" + SampleDirName(index)}};
    SampleRecord record;
    record.index = index;
    try {
        Json files = Simulate(spec, context, index, dir, line);
        line["files"] = std::move(files);
        record.ok = true;
        record.line = line.dump();
        io::WriteTextAtomically(dir / "sample.json", record.line + "\n");
    } catch (const std::exception& e) {
        std::error_code ec;
        fs::remove(dir / "sample.json", ec);  // a stale record must not survive a failure
        line["status"] = "failed";
        line["error"] = e.what();
        record.line = line.dump();
    }
    return record;
}

}  // namespace casmap::pipeline
