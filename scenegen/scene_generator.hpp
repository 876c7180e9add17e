#pragma once

// Procedural scenes for datasets: flat obstacle courses beyond the paper's Table I (boxes,
// drums, poles down to 2.5 mm, ramps, curbs, steps, rocks, holes and ditches) and terrains
// (fractal heightfields with bumps and ruts, obstacles standing on the surface). A scene is a
// pure function of (config, seed). Objects never overlap each other (their footprints' bounding
// circles keep min_gap_m apart) and stay inside the mapped region; the ground covers
// ground_min_xy_m..ground_max_xy_m. Rocks come from unit-sphere meshes the caller names
// (scenes/meshes/rock_*.ply), scaled per axis and rotated.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "casmap/scenegen/heightfield.hpp"
#include "casmap/scenegen/random.hpp"

namespace casmap::scenegen {

/// Obstacle kinds, in the order of SceneGenConfig::kind_weights.
enum class ObjectKind : std::uint8_t { kBox, kDrum, kPole, kRamp, kCurb, kStep, kRock };
inline constexpr std::size_t kObjectKinds = 7;
[[nodiscard]] const char* ObjectKindName(ObjectKind kind);

/// A named Range with the physical bounds a spec may not leave (for validation and YAML).
struct RangeField {
    const char* key;
    Range* range;
    double lo;
    double hi;
};

struct SceneGenConfig {
    // Where: the mapped region (objects stay inside) and the ground's extent (set by the caller
    // from the rig; not part of the spec).
    Eigen::Vector2d region_min_xy_m{1.0, -1.0};
    Eigen::Vector2d region_max_xy_m{6.0, 1.0};
    Eigen::Vector2d ground_min_xy_m{-1.0, -2.0};
    Eigen::Vector2d ground_max_xy_m{7.0, 2.0};
    /// Keep-out rectangle for obstacles (the vehicle's lane); empty when min > max.
    Eigen::Vector2d keep_out_min_xy_m{1.0, 0.0};
    Eigen::Vector2d keep_out_max_xy_m{0.0, 0.0};

    double terrain_probability = 0.5;  // else a flat course
    double ground_cell_m = 0.05;       // heightfield spacing (terrain and flat ground)
    // Terrain relief.
    Range noise_amplitude_m{0.02, 0.10};
    Range noise_wavelength_m{0.6, 2.0};
    int noise_octaves = 3;
    double max_slope_deg = 20.0;
    Range bumps_per_m2{0.0, 0.3};
    Range bump_radius_m{0.2, 0.6};
    Range bump_height_m{-0.08, 0.12};
    Range ruts{0.0, 2.0};
    Range rut_width_m{0.1, 0.25};
    Range rut_depth_m{0.02, 0.06};
    // Negative obstacles (both scene types).
    Range holes{0.0, 2.0};
    Range hole_radius_m{0.08, 0.3};
    Range hole_depth_m{0.05, 0.3};
    Range ditches{0.0, 1.0};
    Range ditch_width_m{0.15, 0.4};
    Range ditch_depth_m{0.05, 0.25};
    // Obstacles: how many (per m^2 of the region) and of which kind.
    Range clutter_per_m2{0.3, 1.2};
    std::array<double, kObjectKinds> kind_weights{3.0, 1.0, 3.0, 0.5, 0.5, 0.5, 2.0};
    double terrain_rock_weight_factor = 3.0;  // rocks are likelier on terrain
    Range box_size_m{0.08, 0.6};
    Range box_height_m{0.05, 0.5};
    Range drum_radius_m{0.15, 0.3};
    Range drum_height_m{0.4, 0.9};
    Range pole_diameter_m{0.0025, 0.05};
    Range pole_height_m{0.3, 1.0};
    Range ramp_length_m{0.5, 1.2};
    Range ramp_width_m{0.4, 1.0};
    Range ramp_angle_deg{5.0, 20.0};
    Range curb_length_m{0.5, 1.5};
    Range curb_height_m{0.05, 0.2};
    Range step_size_m{0.4, 1.0};
    Range step_height_m{0.05, 0.25};
    Range rock_size_m{0.05, 0.35};
    double min_gap_m = 0.05;
    // Materials: diffuse reflectance at 905 nm, from one of three classes per object.
    double p_dark = 0.15;
    double p_bright = 0.15;
    // Retro-reflectors (sheeting, reflector posts): their `reflectivity` scales the sensor's
    // retro_gain; they dazzle the scanner when close (docs/scenes.md "Materials").
    double p_retro = 0.03;
    Range dark_reflectivity{0.02, 0.08};
    Range normal_reflectivity{0.1, 0.6};
    Range bright_reflectivity{0.6, 1.0};
    Range retro_reflectivity{0.3, 1.0};
    Range ground_reflectivity{0.1, 0.5};

    /// Every Range field with its key and allowed bounds.
    [[nodiscard]] std::vector<RangeField> Ranges();
    /// Throws InputError "<where>: scene.<key> = <value> (<rule>)" for the first bad field.
    void Validate(const std::string& where) const;
};

/// One generated object, as a scene file writes it.
struct GenObject {
    std::string name;
    ObjectKind kind = ObjectKind::kBox;
    Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();  // kBox, kRamp, kCurb, kStep
    double radius_m = 0.0;                                 // kDrum, kPole
    double height_m = 0.0;                                 // kDrum, kPole
    int rock_mesh = 0;                                     // kRock: index into the rock list
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();       // kRock: per-axis size (m)
    Eigen::Vector3d xyz_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
    double reflectivity = 0.5;
    bool retro_reflective = false;
};

struct NegativeObstacle {
    bool ditch = false;  // else a round hole
    Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
    double size_m = 0.0;  // hole radius or ditch width
    double depth_m = 0.0;
};

struct GeneratedScene {
    bool terrain = false;
    Heightfield ground;
    double ground_reflectivity = 0.3;
    std::vector<GenObject> objects;
    std::vector<NegativeObstacle> negatives;
    int placement_failures = 0;  // obstacles dropped because no free spot was found
};

/// The scene for `seed`. `rock_meshes` = how many rock meshes the caller offers (0: no rocks).
[[nodiscard]] GeneratedScene GenerateScene(const SceneGenConfig& config,
                                           std::uint64_t seed,
                                           int rock_meshes);

}  // namespace casmap::scenegen
