#include "casmap/scenegen/scene_generator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/scenegen/scene_writer.hpp"

namespace casmap::scenegen {
namespace {

constexpr int kPlacementTries = 60;

struct Footprint {
    Eigen::Vector2d xy_m;
    double radius_m = 0.0;
};

// Occupied ground: object footprints, holes (circles) and ditches (bands across the track).
struct Occupancy {
    const SceneGenConfig* config = nullptr;
    std::vector<Footprint> circles;
    std::vector<Eigen::Vector2d> bands;  // (x centre, half width)

    [[nodiscard]] bool Free(const Eigen::Vector2d& c, double r) const {
        const SceneGenConfig& k = *config;
        if (c.x() - r < k.region_min_xy_m.x() || c.x() + r > k.region_max_xy_m.x() ||
            c.y() - r < k.region_min_xy_m.y() || c.y() + r > k.region_max_xy_m.y()) {
            return false;
        }
        if (k.keep_out_min_xy_m.x() <= k.keep_out_max_xy_m.x()) {
            const Eigen::Vector2d nearest =
                c.cwiseMax(k.keep_out_min_xy_m).cwiseMin(k.keep_out_max_xy_m);
            if ((nearest - c).norm() < r + k.min_gap_m) {
                return false;
            }
        }
        for (const Footprint& f : circles) {
            if ((f.xy_m - c).norm() < f.radius_m + r + k.min_gap_m) {
                return false;
            }
        }
        for (const Eigen::Vector2d& b : bands) {
            if (std::abs(b.x() - c.x()) < b.y() + r + k.min_gap_m) {
                return false;
            }
        }
        return true;
    }

    // A free spot for a footprint of radius r, or false after kPlacementTries draws.
    bool Place(double r, Rng& rng, Eigen::Vector2d& out) const {
        const SceneGenConfig& k = *config;
        for (int t = 0; t < kPlacementTries; ++t) {
            const Eigen::Vector2d c(rng.Draw({k.region_min_xy_m.x(), k.region_max_xy_m.x()}),
                                    rng.Draw({k.region_min_xy_m.y(), k.region_max_xy_m.y()}));
            if (Free(c, r)) {
                out = c;
                return true;
            }
        }
        return false;
    }
};

// One uniform draw picks the class (dark, bright, retro-reflective, normal), one the value.
void DrawMaterial(const SceneGenConfig& k, Rng& rng, GenObject& o) {
    const double u = rng.Uniform();
    o.retro_reflective = false;
    const Range* r = &k.normal_reflectivity;
    if (u < k.p_dark) {
        r = &k.dark_reflectivity;
    } else if (u < k.p_dark + k.p_bright) {
        r = &k.bright_reflectivity;
    } else if (u < k.p_dark + k.p_bright + k.p_retro) {
        r = &k.retro_reflectivity;
        o.retro_reflective = true;
    }
    o.reflectivity = rng.Draw(*r);
}

// Shape of one obstacle (sizes, orientation) and its footprint radius; position comes later.
GenObject DrawShape(const SceneGenConfig& k, ObjectKind kind, int rock_meshes, Rng& rng) {
    GenObject o;
    o.kind = kind;
    const double yaw = rng.Draw({0.0, 180.0});
    o.rpy_deg = {0.0, 0.0, yaw};
    switch (kind) {
        case ObjectKind::kBox:
            o.box_size_m = {rng.Draw(k.box_size_m), rng.Draw(k.box_size_m),
                            rng.Draw(k.box_height_m)};
            break;
        case ObjectKind::kDrum:
            o.radius_m = rng.Draw(k.drum_radius_m);
            o.height_m = rng.Draw(k.drum_height_m);
            o.rpy_deg.z() = 0.0;
            break;
        case ObjectKind::kPole:
            o.radius_m = 0.5 * rng.Draw(k.pole_diameter_m);
            o.height_m = rng.Draw(k.pole_height_m);
            o.rpy_deg.z() = 0.0;
            break;
        case ObjectKind::kRamp:
            o.box_size_m = {rng.Draw(k.ramp_length_m), rng.Draw(k.ramp_width_m), 0.04};
            o.rpy_deg.y() = -rng.Draw(k.ramp_angle_deg);  // rises towards its +x end
            break;
        case ObjectKind::kCurb:
            o.box_size_m = {0.15, rng.Draw(k.curb_length_m), rng.Draw(k.curb_height_m)};
            break;
        case ObjectKind::kStep:
            o.box_size_m = {rng.Draw(k.step_size_m), rng.Draw(k.step_size_m),
                            rng.Draw(k.step_height_m)};
            break;
        case ObjectKind::kRock: {
            o.rock_mesh = static_cast<int>(rng.Below(static_cast<std::uint64_t>(rock_meshes)));
            const double size = rng.Draw(k.rock_size_m);
            o.scale = {size * rng.Draw({0.7, 1.3}), size * rng.Draw({0.7, 1.3}),
                       size * rng.Draw({0.5, 1.0})};
            o.rpy_deg = {rng.Draw({-20.0, 20.0}), rng.Draw({-20.0, 20.0}), yaw * 2.0};
            break;
        }
    }
    DrawMaterial(k, rng, o);
    return o;
}

double FootprintRadius(const GenObject& o) {
    switch (o.kind) {
        case ObjectKind::kDrum:
        case ObjectKind::kPole:
            return o.radius_m;
        case ObjectKind::kRock:
            return std::max(o.scale.x(), o.scale.y());
        default:
            return 0.5 * std::hypot(o.box_size_m.x(), o.box_size_m.y());
    }
}

// Stands the object on the ground: its lowest point at the lowest ground under its footprint.
void StandOnGround(GenObject& o, const Heightfield& ground, double radius_m) {
    const double base = ground.HeightSpan(o.xyz_m.head<2>(), radius_m)[0];
    switch (o.kind) {
        case ObjectKind::kDrum:
        case ObjectKind::kPole:
            o.xyz_m.z() = base + 0.5 * o.height_m;
            break;
        case ObjectKind::kRamp: {
            const double angle = std::abs(o.rpy_deg.y()) * std::numbers::pi / 180.0;
            o.xyz_m.z() = base + 0.5 * o.box_size_m.x() * std::sin(angle);
            break;
        }
        case ObjectKind::kRock:
            o.xyz_m.z() = base + 0.4 * o.scale.z();  // partly buried
            break;
        default:
            o.xyz_m.z() = base + 0.5 * o.box_size_m.z();
    }
}

void ShapeTerrain(const SceneGenConfig& k, GeneratedScene& s, Rng& rng) {
    AddFractalNoise(s.ground, rng.Draw(k.noise_amplitude_m), rng.Draw(k.noise_wavelength_m),
                    k.noise_octaves, rng);
    const Eigen::Vector2d lo = k.ground_min_xy_m;
    const Eigen::Vector2d hi = k.ground_max_xy_m;
    const double area = (hi - lo).prod();
    const int bumps = static_cast<int>(std::lround(rng.Draw(k.bumps_per_m2) * area));
    for (int b = 0; b < bumps; ++b) {
        const Eigen::Vector2d c(rng.Draw({lo.x(), hi.x()}), rng.Draw({lo.y(), hi.y()}));
        AddBump(s.ground, c, rng.Draw(k.bump_radius_m), rng.Draw(k.bump_height_m));
    }
    const int ruts = rng.Count(k.ruts);
    for (int r = 0; r < ruts; ++r) {
        AddRut(s.ground, rng.Draw({k.region_min_xy_m.y(), k.region_max_xy_m.y()}),
               rng.Draw(k.rut_width_m), rng.Draw(k.rut_depth_m));
    }
    LimitSlope(s.ground, k.max_slope_deg);
}

void CarveNegatives(const SceneGenConfig& k, GeneratedScene& s, Occupancy& occ, Rng& rng) {
    const int holes = rng.Count(k.holes);
    for (int h = 0; h < holes; ++h) {
        NegativeObstacle n;
        n.size_m = rng.Draw(k.hole_radius_m);
        n.depth_m = rng.Draw(k.hole_depth_m);
        if (!occ.Place(n.size_m, rng, n.xy_m)) {
            ++s.placement_failures;
            continue;
        }
        CarveHole(s.ground, n.xy_m, n.size_m, n.depth_m);
        occ.circles.push_back({n.xy_m, n.size_m});
        s.negatives.push_back(n);
    }
    const int ditches = rng.Count(k.ditches);
    for (int d = 0; d < ditches; ++d) {
        NegativeObstacle n;
        n.ditch = true;
        n.size_m = rng.Draw(k.ditch_width_m);
        n.depth_m = rng.Draw(k.ditch_depth_m);
        const double half = 0.5 * n.size_m;
        n.xy_m = {rng.Draw({k.region_min_xy_m.x() + half, k.region_max_xy_m.x() - half}),
                  0.5 * (k.region_min_xy_m.y() + k.region_max_xy_m.y())};
        bool free = true;
        for (const Footprint& f : occ.circles) {
            free = free && std::abs(f.xy_m.x() - n.xy_m.x()) >= f.radius_m + half + k.min_gap_m;
        }
        for (const Eigen::Vector2d& b : occ.bands) {
            free = free && std::abs(b.x() - n.xy_m.x()) >= b.y() + half + k.min_gap_m;
        }
        if (!free) {
            ++s.placement_failures;
            continue;
        }
        CarveDitch(s.ground, n.xy_m.x(), n.size_m, n.depth_m);
        occ.bands.emplace_back(n.xy_m.x(), half);
        s.negatives.push_back(n);
    }
}

}  // namespace

const char* ObjectKindName(ObjectKind kind) {
    static constexpr const char* kNames[] = {"box", "drum", "pole", "ramp", "curb", "step", "rock"};
    return kNames[static_cast<std::size_t>(kind)];
}

GeneratedScene GenerateScene(const SceneGenConfig& k, std::uint64_t seed, int rock_meshes) {
    Rng rng(seed);
    GeneratedScene s;
    s.terrain = rng.Chance(k.terrain_probability);
    s.ground = Heightfield::Flat(k.ground_min_xy_m, k.ground_max_xy_m, k.ground_cell_m);
    s.ground_reflectivity = rng.Draw(k.ground_reflectivity);
    if (s.terrain) {
        ShapeTerrain(k, s, rng);
    }
    Occupancy occ{&k, {}, {}};
    CarveNegatives(k, s, occ, rng);
    std::array<double, kObjectKinds> weights = k.kind_weights;
    const auto rock = static_cast<std::size_t>(ObjectKind::kRock);
    weights[rock] =
        rock_meshes > 0 ? weights[rock] * (s.terrain ? k.terrain_rock_weight_factor : 1.0) : 0.0;
    const double area = (k.region_max_xy_m - k.region_min_xy_m).prod();
    const int count = static_cast<int>(std::lround(rng.Draw(k.clutter_per_m2) * area));
    int counters[kObjectKinds] = {};
    for (int n = 0; n < count; ++n) {
        const auto kind = static_cast<ObjectKind>(rng.Pick(weights.data(), weights.size()));
        GenObject o = DrawShape(k, kind, rock_meshes, rng);
        const double r = FootprintRadius(o);
        Eigen::Vector2d xy;
        if (!occ.Place(r, rng, xy)) {
            ++s.placement_failures;
            continue;
        }
        o.xyz_m.head<2>() = xy;
        StandOnGround(o, s.ground, r);
        occ.circles.push_back({xy, r});
        const auto kind_index = static_cast<std::size_t>(kind);
        o.name = std::string(ObjectKindName(kind)) + "_" + std::to_string(++counters[kind_index]);
        s.objects.push_back(std::move(o));
    }
    return s;
}

std::vector<RangeField> SceneGenConfig::Ranges() {
    return {{"noise_amplitude_m", &noise_amplitude_m, 0.0, 1.0},
            {"noise_wavelength_m", &noise_wavelength_m, 0.05, 100.0},
            {"bumps_per_m2", &bumps_per_m2, 0.0, 10.0},
            {"bump_radius_m", &bump_radius_m, 0.05, 10.0},
            {"bump_height_m", &bump_height_m, -1.0, 1.0},
            {"ruts", &ruts, 0.0, 10.0},
            {"rut_width_m", &rut_width_m, 0.02, 2.0},
            {"rut_depth_m", &rut_depth_m, 0.0, 0.5},
            {"holes", &holes, 0.0, 20.0},
            {"hole_radius_m", &hole_radius_m, 0.02, 2.0},
            {"hole_depth_m", &hole_depth_m, 0.0, 2.0},
            {"ditches", &ditches, 0.0, 5.0},
            {"ditch_width_m", &ditch_width_m, 0.02, 2.0},
            {"ditch_depth_m", &ditch_depth_m, 0.0, 2.0},
            {"clutter_per_m2", &clutter_per_m2, 0.0, 20.0},
            {"box_size_m", &box_size_m, 0.01, 3.0},
            {"box_height_m", &box_height_m, 0.005, 3.0},
            {"drum_radius_m", &drum_radius_m, 0.01, 1.0},
            {"drum_height_m", &drum_height_m, 0.01, 3.0},
            {"pole_diameter_m", &pole_diameter_m, 0.0025, 0.2},
            {"pole_height_m", &pole_height_m, 0.01, 3.0},
            {"ramp_length_m", &ramp_length_m, 0.1, 5.0},
            {"ramp_width_m", &ramp_width_m, 0.1, 3.0},
            {"ramp_angle_deg", &ramp_angle_deg, 0.0, 45.0},
            {"curb_length_m", &curb_length_m, 0.1, 5.0},
            {"curb_height_m", &curb_height_m, 0.01, 0.5},
            {"step_size_m", &step_size_m, 0.1, 5.0},
            {"step_height_m", &step_height_m, 0.01, 1.0},
            {"rock_size_m", &rock_size_m, 0.01, 2.0},
            {"dark_reflectivity", &dark_reflectivity, 0.0, 1.0},
            {"normal_reflectivity", &normal_reflectivity, 0.0, 1.0},
            {"bright_reflectivity", &bright_reflectivity, 0.0, 1.0},
            {"retro_reflectivity", &retro_reflectivity, 0.0, 1.0},
            {"ground_reflectivity", &ground_reflectivity, 0.0, 1.0}};
}

void SceneGenConfig::Validate(const std::string& where) const {
    const core::Check check(where, "scene.");
    SceneGenConfig copy = *this;  // Ranges() hands out pointers into its object
    for (const RangeField& f : copy.Ranges()) {
        const Range& r = *f.range;
        if (!(std::isfinite(r.min) && std::isfinite(r.max) && f.lo <= r.min && r.min <= r.max &&
              r.max <= f.hi)) {
            check.Fail(
                f.key, "[" + FormatNumber(r.min) + ", " + FormatNumber(r.max) + "]",
                "allowed: " + FormatNumber(f.lo) + " <= min <= max <= " + FormatNumber(f.hi));
        }
    }
    if (!(terrain_probability >= 0.0 && terrain_probability <= 1.0)) {
        check.Fail("terrain_probability", FormatNumber(terrain_probability), "allowed: 0..1");
    }
    if (!(ground_cell_m >= 0.01 && ground_cell_m <= 0.5)) {
        check.Fail("ground_cell_m", FormatNumber(ground_cell_m), "allowed: 0.01..0.5");
    }
    if (noise_octaves < 1 || noise_octaves > 8) {
        check.Fail("noise_octaves", std::to_string(noise_octaves), "allowed: 1..8");
    }
    if (!(max_slope_deg > 0.0 && max_slope_deg <= 60.0)) {
        check.Fail("max_slope_deg", FormatNumber(max_slope_deg), "allowed: > 0 and <= 60");
    }
    double total = 0.0;
    for (const double w : kind_weights) {
        if (!(w >= 0.0 && std::isfinite(w))) {
            check.Fail("kind_weights", FormatNumber(w), "each weight must be finite and >= 0");
        }
        total += w;
    }
    if (!(total > 0.0)) {
        check.Fail("kind_weights", "all 0", "at least one weight must be > 0");
    }
    if (!(terrain_rock_weight_factor >= 0.0 && terrain_rock_weight_factor <= 100.0)) {
        check.Fail("terrain_rock_weight_factor", FormatNumber(terrain_rock_weight_factor),
                   "allowed: 0..100");
    }
    if (!(min_gap_m >= 0.0 && min_gap_m <= 1.0)) {
        check.Fail("min_gap_m", FormatNumber(min_gap_m), "allowed: 0..1");
    }
    if (!(p_dark >= 0.0 && p_bright >= 0.0 && p_retro >= 0.0 &&
          p_dark + p_bright + p_retro <= 1.0)) {
        check.Fail("p_dark",
                   FormatNumber(p_dark) + " + p_bright " + FormatNumber(p_bright) + " + p_retro " +
                       FormatNumber(p_retro),
                   "allowed: each >= 0, sum <= 1");
    }
}

}  // namespace casmap::scenegen
