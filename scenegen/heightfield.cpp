#include "casmap/scenegen/heightfield.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace casmap::scenegen {
namespace {

double Smooth(double t) { return t * t * (3.0 - 2.0 * t); }

// One octave of value noise: random values on a lattice of `wavelength_m`, smoothly blended.
void AddOctave(Heightfield& f, double amplitude_m, double wavelength_m, Rng& rng) {
    const double x_span = (f.nx - 1) * f.cell_m;
    const double y_span = (f.ny - 1) * f.cell_m;
    const int lx = static_cast<int>(std::ceil(x_span / wavelength_m)) + 2;
    const int ly = static_cast<int>(std::ceil(y_span / wavelength_m)) + 2;
    std::vector<double> lattice(static_cast<std::size_t>(lx * ly));
    for (double& v : lattice) {
        v = (2.0 * rng.Uniform() - 1.0) * amplitude_m;
    }
    const auto value = [&](int a, int b) { return lattice[static_cast<std::size_t>(a * ly + b)]; };
    for (int i = 0; i < f.nx; ++i) {
        const double u = i * f.cell_m / wavelength_m;
        const int a = static_cast<int>(u);
        const double s = Smooth(u - a);
        for (int j = 0; j < f.ny; ++j) {
            const double v = j * f.cell_m / wavelength_m;
            const int b = static_cast<int>(v);
            const double t = Smooth(v - b);
            const double z0 = value(a, b) + (value(a + 1, b) - value(a, b)) * s;
            const double z1 = value(a, b + 1) + (value(a + 1, b + 1) - value(a, b + 1)) * s;
            f.At(i, j) += static_cast<float>(z0 + (z1 - z0) * t);
        }
    }
}

}  // namespace

Heightfield Heightfield::Flat(const Eigen::Vector2d& min_xy_m,
                              const Eigen::Vector2d& max_xy_m,
                              double cell_m) {
    Heightfield f;
    f.x0_m = min_xy_m.x();
    f.y0_m = min_xy_m.y();
    f.cell_m = cell_m;
    f.nx = std::max(2, static_cast<int>(std::ceil((max_xy_m.x() - min_xy_m.x()) / cell_m)) + 1);
    f.ny = std::max(2, static_cast<int>(std::ceil((max_xy_m.y() - min_xy_m.y()) / cell_m)) + 1);
    f.z_m.assign(static_cast<std::size_t>(f.nx * f.ny), 0.0F);
    return f;
}

double Heightfield::HeightAt(double x_m, double y_m) const {
    const double u = std::clamp((x_m - x0_m) / cell_m, 0.0, nx - 1.0);
    const double v = std::clamp((y_m - y0_m) / cell_m, 0.0, ny - 1.0);
    const int i = std::min(static_cast<int>(u), nx - 2);
    const int j = std::min(static_cast<int>(v), ny - 2);
    const double s = u - i;
    const double t = v - j;
    const double z0 = At(i, j) + (At(i + 1, j) - At(i, j)) * s;
    const double z1 = At(i, j + 1) + (At(i + 1, j + 1) - At(i, j + 1)) * s;
    return z0 + (z1 - z0) * t;
}

Eigen::Vector2d Heightfield::HeightSpan(const Eigen::Vector2d& xy_m, double radius_m) const {
    const int i0 = std::max(0, static_cast<int>(std::floor((xy_m.x() - radius_m - x0_m) / cell_m)));
    const int i1 =
        std::min(nx - 1, static_cast<int>(std::ceil((xy_m.x() + radius_m - x0_m) / cell_m)));
    const int j0 = std::max(0, static_cast<int>(std::floor((xy_m.y() - radius_m - y0_m) / cell_m)));
    const int j1 =
        std::min(ny - 1, static_cast<int>(std::ceil((xy_m.y() + radius_m - y0_m) / cell_m)));
    const double centre = HeightAt(xy_m.x(), xy_m.y());
    Eigen::Vector2d span(centre, centre);
    for (int i = i0; i <= i1; ++i) {
        for (int j = j0; j <= j1; ++j) {
            if ((XY(i, j) - xy_m).norm() <= radius_m + cell_m) {
                span[0] = std::min(span[0], static_cast<double>(At(i, j)));
                span[1] = std::max(span[1], static_cast<double>(At(i, j)));
            }
        }
    }
    return span;
}

double Heightfield::MaxSlopeDeg() const {
    double steepest = 0.0;
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            if (i + 1 < nx) {
                steepest = std::max(steepest, std::abs(At(i + 1, j) - At(i, j)) / cell_m);
            }
            if (j + 1 < ny) {
                steepest = std::max(steepest, std::abs(At(i, j + 1) - At(i, j)) / cell_m);
            }
        }
    }
    return std::atan(steepest) * 180.0 / std::numbers::pi;
}

void AddFractalNoise(
    Heightfield& field, double amplitude_m, double wavelength_m, int octaves, Rng& rng) {
    double amplitude = amplitude_m;
    double wavelength = wavelength_m;
    for (int k = 0; k < octaves; ++k) {
        AddOctave(field, amplitude, std::max(wavelength, 2.0 * field.cell_m), rng);
        amplitude *= 0.5;
        wavelength *= 0.5;
    }
}

void AddBump(Heightfield& field, const Eigen::Vector2d& xy_m, double radius_m, double height_m) {
    for (int i = 0; i < field.nx; ++i) {
        for (int j = 0; j < field.ny; ++j) {
            const double r = (field.XY(i, j) - xy_m).norm();
            if (r < radius_m) {
                const double w = 0.5 * (1.0 + std::cos(std::numbers::pi * r / radius_m));
                field.At(i, j) += static_cast<float>(height_m * w);
            }
        }
    }
}

void AddRut(Heightfield& field, double y_m, double width_m, double depth_m) {
    const double half = 0.5 * width_m;
    for (int j = 0; j < field.ny; ++j) {
        const double d = std::abs(field.y0_m + j * field.cell_m - y_m);
        if (d >= half) {
            continue;
        }
        const double w = 0.5 * (1.0 + std::cos(std::numbers::pi * d / half));
        for (int i = 0; i < field.nx; ++i) {
            field.At(i, j) -= static_cast<float>(depth_m * w);
        }
    }
}

void LimitSlope(Heightfield& field, double max_slope_deg) {
    const double slope = field.MaxSlopeDeg();
    if (slope <= max_slope_deg || slope <= 0.0) {
        return;
    }
    const double factor = std::tan(max_slope_deg * std::numbers::pi / 180.0) /
                          std::tan(slope * std::numbers::pi / 180.0);
    for (float& z : field.z_m) {
        z = static_cast<float>(z * factor);
    }
}

void CarveHole(Heightfield& field, const Eigen::Vector2d& xy_m, double radius_m, double depth_m) {
    const float bottom = static_cast<float>(field.HeightAt(xy_m.x(), xy_m.y()) - depth_m);
    for (int i = 0; i < field.nx; ++i) {
        for (int j = 0; j < field.ny; ++j) {
            if ((field.XY(i, j) - xy_m).norm() <= radius_m) {
                field.At(i, j) = std::min(field.At(i, j), bottom);
            }
        }
    }
}

void CarveDitch(Heightfield& field, double x_m, double width_m, double depth_m) {
    for (int i = 0; i < field.nx; ++i) {
        if (std::abs(field.x0_m + i * field.cell_m - x_m) > 0.5 * width_m) {
            continue;
        }
        for (int j = 0; j < field.ny; ++j) {
            field.At(i, j) -= static_cast<float>(depth_m);
        }
    }
}

core::MeshShape ToMesh(const Heightfield& field) {
    core::MeshShape mesh;
    mesh.source_path = "generated heightfield";
    mesh.vertices.reserve(field.z_m.size());
    for (int i = 0; i < field.nx; ++i) {
        for (int j = 0; j < field.ny; ++j) {
            const Eigen::Vector2d xy = field.XY(i, j);
            mesh.vertices.emplace_back(static_cast<float>(xy.x()), static_cast<float>(xy.y()),
                                       field.At(i, j));
        }
    }
    mesh.triangles.reserve(static_cast<std::size_t>(2 * (field.nx - 1) * (field.ny - 1)));
    for (int i = 0; i + 1 < field.nx; ++i) {
        for (int j = 0; j + 1 < field.ny; ++j) {
            const int a = i * field.ny + j;
            const int b = (i + 1) * field.ny + j;
            const int c = (i + 1) * field.ny + j + 1;
            const int d = i * field.ny + j + 1;
            mesh.triangles.emplace_back(a, b, c);  // x then y: counter-clockwise from above
            mesh.triangles.emplace_back(a, c, d);
        }
    }
    return mesh;
}

}  // namespace casmap::scenegen
