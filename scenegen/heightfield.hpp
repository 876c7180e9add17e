#pragma once

// Ground surfaces of generated scenes: a regular grid of heights (world z, m) triangulated into
// a mesh. Terrain relief (fractal value noise, bumps, ruts) is shaped first and scaled to a
// slope limit; negative obstacles (holes, ditches) are carved afterwards with steep walls.

#include <Eigen/Core>
#include <vector>

#include "casmap/core/scene.hpp"
#include "casmap/scenegen/random.hpp"

namespace casmap::scenegen {

/// Heights at the vertices (x0 + i cell, y0 + j cell), i in [0, nx), j in [0, ny).
struct Heightfield {
    double x0_m = 0.0;
    double y0_m = 0.0;
    double cell_m = 0.05;
    int nx = 2;
    int ny = 2;
    std::vector<float> z_m;  // index i * ny + j

    [[nodiscard]] static Heightfield Flat(const Eigen::Vector2d& min_xy_m,
                                          const Eigen::Vector2d& max_xy_m,
                                          double cell_m);
    [[nodiscard]] float& At(int i, int j) { return z_m[static_cast<std::size_t>(i * ny + j)]; }
    [[nodiscard]] float At(int i, int j) const { return z_m[static_cast<std::size_t>(i * ny + j)]; }
    [[nodiscard]] Eigen::Vector2d XY(int i, int j) const {
        return {x0_m + i * cell_m, y0_m + j * cell_m};
    }
    /// Bilinear height at (x, y) (m); clamped to the grid's edge outside it.
    [[nodiscard]] double HeightAt(double x_m, double y_m) const;
    /// Lowest and highest vertex height within `radius_m` of (x, y) (m).
    [[nodiscard]] Eigen::Vector2d HeightSpan(const Eigen::Vector2d& xy_m, double radius_m) const;
    /// Steepest slope between neighbouring vertices (deg).
    [[nodiscard]] double MaxSlopeDeg() const;
};

/// Adds fractal value noise: `octaves` layers, wavelength halving and amplitude halving per
/// octave, peak amplitude about `amplitude_m`.
void AddFractalNoise(
    Heightfield& field, double amplitude_m, double wavelength_m, int octaves, Rng& rng);
/// Adds a smooth cosine bump (negative height: a dip) of `radius_m` centred on `xy_m`.
void AddBump(Heightfield& field, const Eigen::Vector2d& xy_m, double radius_m, double height_m);
/// Lowers a rut along world x at `y_m` with a cosine cross-section of `width_m`.
void AddRut(Heightfield& field, double y_m, double width_m, double depth_m);
/// Scales every height so that the steepest slope is at most `max_slope_deg`.
void LimitSlope(Heightfield& field, double max_slope_deg);
/// Carves a round hole of flat bottom `depth_m` below the local surface.
void CarveHole(Heightfield& field, const Eigen::Vector2d& xy_m, double radius_m, double depth_m);
/// Carves a ditch across the track (along y) at `x_m`, `width_m` wide, `depth_m` deep.
void CarveDitch(Heightfield& field, double x_m, double width_m, double depth_m);

/// Two triangles per cell, normals up (counter-clockwise seen from above).
[[nodiscard]] core::MeshShape ToMesh(const Heightfield& field);

}  // namespace casmap::scenegen
