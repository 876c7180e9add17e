#include "casmap/sim/ground_truth.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/text.hpp"
#include "casmap/sim/box_shape.hpp"

namespace casmap::sim {
namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

struct Triangle {
    std::array<Eigen::Vector3d, 3> v;
};

// A vertical cylinder seen from above: its top disc covers everything the cylinder covers.
struct Disc {
    double cx = 0.0;
    double cy = 0.0;
    double radius = 0.0;
    double top_z = 0.0;
};

struct Primitives {
    std::vector<Triangle> triangles;
    std::vector<Disc> discs;
};

void AddBox(const core::BoxShape& box, const core::Pose& pose, Primitives& out) {
    const std::array<Eigen::Vector3d, 8> p = BoxCorners(box, pose);
    for (const auto& t : kBoxTriangles) {
        out.triangles.push_back(
            {{p[static_cast<std::size_t>(t[0])], p[static_cast<std::size_t>(t[1])],
              p[static_cast<std::size_t>(t[2])]}});
    }
}

void AddCylinder(const core::CylinderShape& cyl,
                 const core::Pose& pose,
                 int segments,
                 Primitives& out) {
    const Eigen::Matrix3d rot = pose.rotation.normalized().toRotationMatrix();
    const double h = 0.5 * cyl.height_m;
    if (std::abs(rot(2, 2)) == 1.0) {  // axis exactly vertical: the exact disc
        out.discs.push_back(
            {pose.translation.x(), pose.translation.y(), cyl.radius_m, pose.translation.z() + h});
        return;
    }
    const Eigen::Vector3d bottom = pose * Eigen::Vector3d(0, 0, -h);
    const Eigen::Vector3d top = pose * Eigen::Vector3d(0, 0, h);
    for (int k = 0; k < segments; ++k) {
        const auto rim = [&](int i, double z) {
            const double a = 2.0 * std::numbers::pi * i / segments;
            return pose *
                   Eigen::Vector3d(cyl.radius_m * std::cos(a), cyl.radius_m * std::sin(a), z);
        };
        const Eigen::Vector3d b0 = rim(k, -h);
        const Eigen::Vector3d b1 = rim(k + 1, -h);
        const Eigen::Vector3d t0 = rim(k, h);
        const Eigen::Vector3d t1 = rim(k + 1, h);
        out.triangles.push_back({{b0, b1, t1}});
        out.triangles.push_back({{b0, t1, t0}});
        out.triangles.push_back({{bottom, b1, b0}});
        out.triangles.push_back({{top, t0, t1}});
    }
}

Primitives CollectPrimitives(const core::Scene& scene, int segments) {
    Primitives out;
    for (const core::SceneObject& object : scene.objects) {
        const core::Pose& pose = object.world_T_object;
        if (const auto* box = std::get_if<core::BoxShape>(&object.shape)) {
            AddBox(*box, pose, out);
        } else if (const auto* cyl = std::get_if<core::CylinderShape>(&object.shape)) {
            AddCylinder(*cyl, pose, segments, out);
        } else {
            const auto& mesh = std::get<core::MeshShape>(object.shape);
            const auto vertex = [&](int i) {
                return pose * mesh.vertices[static_cast<std::size_t>(i)].cast<double>();
            };
            for (const Eigen::Vector3i& t : mesh.triangles) {
                out.triangles.push_back({{vertex(t[0]), vertex(t[1]), vertex(t[2])}});
            }
        }
    }
    return out;
}

// A convex polygon in 3-D (a triangle clipped by up to four axis-aligned half-planes).
struct Polygon {
    std::array<Eigen::Vector3d, 8> v{};
    int n = 0;
};

// Keeps the part of `in` with p[axis] >= bound (keep_above) or <= bound. Points created on
// the boundary get exactly `bound`, so later "lies on the boundary" tests are exact.
Polygon Clip(const Polygon& in, int axis, double bound, bool keep_above) {
    Polygon out;
    const auto inside = [&](const Eigen::Vector3d& p) {
        return keep_above ? p[axis] >= bound : p[axis] <= bound;
    };
    for (int i = 0; i < in.n; ++i) {
        const Eigen::Vector3d& a = in.v[static_cast<std::size_t>(i)];
        const Eigen::Vector3d& b = in.v[static_cast<std::size_t>((i + 1) % in.n)];
        const bool a_in = inside(a);
        const bool b_in = inside(b);
        if (a_in) {
            out.v[static_cast<std::size_t>(out.n++)] = a;
        }
        if (a_in != b_in) {
            const double t = (bound - a[axis]) / (b[axis] - a[axis]);
            Eigen::Vector3d p = a + t * (b - a);
            p[axis] = bound;
            out.v[static_cast<std::size_t>(out.n++)] = p;
        }
    }
    return out;
}

// Half-open index range [first, last] of cells whose closed extent meets [lo, hi].
void CellRange(double lo, double hi, double origin, double cell, int count, int& first, int& last) {
    first = std::max(0, static_cast<int>(std::floor((lo - origin) / cell)));
    last = std::min(count - 1, static_cast<int>(std::floor((hi - origin) / cell)));
}

// Rows each primitive may touch (by bounding box), so rows can be processed in parallel.
struct RowBins {
    std::vector<std::vector<std::uint32_t>> triangles;
    std::vector<std::vector<std::uint32_t>> discs;
};

RowBins BinByRow(const Primitives& prims, const core::GridGeometry& grid) {
    RowBins bins;
    bins.triangles.resize(static_cast<std::size_t>(grid.rows));
    bins.discs.resize(static_cast<std::size_t>(grid.rows));
    const auto add = [&](double lo, double hi, std::vector<std::vector<std::uint32_t>>& to,
                         std::size_t index) {
        int first = 0;
        int last = 0;
        CellRange(lo, hi, grid.x0_m, grid.cell_m, grid.rows, first, last);
        for (int r = first; r <= last; ++r) {
            to[static_cast<std::size_t>(r)].push_back(static_cast<std::uint32_t>(index));
        }
    };
    for (std::size_t i = 0; i < prims.triangles.size(); ++i) {
        const auto& v = prims.triangles[i].v;
        add(std::min({v[0].x(), v[1].x(), v[2].x()}), std::max({v[0].x(), v[1].x(), v[2].x()}),
            bins.triangles, i);
    }
    for (std::size_t i = 0; i < prims.discs.size(); ++i) {
        const Disc& d = prims.discs[i];
        add(d.cx - d.radius, d.cx + d.radius, bins.discs, i);
    }
    return bins;
}

// Highest point of every cell of row r (any-overlap rule), into row_out[cols].
void HighestInRow(const Primitives& prims,
                  const RowBins& bins,
                  const core::GridGeometry& grid,
                  int r,
                  double* row_out) {
    const double x_lo = grid.x0_m + r * grid.cell_m;
    const double x_hi = grid.x0_m + (r + 1) * grid.cell_m;
    for (const std::uint32_t i : bins.triangles[static_cast<std::size_t>(r)]) {
        Polygon tri;
        for (std::size_t k = 0; k < 3; ++k) {
            tri.v[k] = prims.triangles[i].v[k];
        }
        tri.n = 3;
        const Polygon strip = Clip(Clip(tri, 0, x_lo, true), 0, x_hi, false);
        if (strip.n == 0) {
            continue;
        }
        double y_min = strip.v[0].y();
        double y_max = y_min;
        for (int k = 1; k < strip.n; ++k) {
            y_min = std::min(y_min, strip.v[static_cast<std::size_t>(k)].y());
            y_max = std::max(y_max, strip.v[static_cast<std::size_t>(k)].y());
        }
        int c0 = 0;
        int c1 = 0;
        CellRange(y_min, y_max, grid.y0_m, grid.cell_m, grid.cols, c0, c1);
        for (int c = c0; c <= c1; ++c) {
            const double y_lo = grid.y0_m + c * grid.cell_m;
            const double y_hi = grid.y0_m + (c + 1) * grid.cell_m;
            const Polygon piece = Clip(Clip(strip, 1, y_lo, true), 1, y_hi, false);
            bool on_x_hi = true;  // a piece lying only on the cell's far edges belongs to the
            bool on_y_hi = true;  // next cell (cells are half-open)
            double z = kNone;
            for (int k = 0; k < piece.n; ++k) {
                const Eigen::Vector3d& p = piece.v[static_cast<std::size_t>(k)];
                on_x_hi = on_x_hi && p.x() == x_hi;
                on_y_hi = on_y_hi && p.y() == y_hi;
                z = std::max(z, p.z());
            }
            if (piece.n > 0 && !on_x_hi && !on_y_hi) {
                row_out[c] = std::max(row_out[c], z);
            }
        }
    }
    for (const std::uint32_t i : bins.discs[static_cast<std::size_t>(r)]) {
        const Disc& d = prims.discs[i];
        if (d.cx - d.radius >= x_hi) {
            continue;
        }
        int c0 = 0;
        int c1 = 0;
        CellRange(d.cy - d.radius, d.cy + d.radius, grid.y0_m, grid.cell_m, grid.cols, c0, c1);
        for (int c = c0; c <= c1; ++c) {
            const double y_lo = grid.y0_m + c * grid.cell_m;
            const double y_hi = grid.y0_m + (c + 1) * grid.cell_m;
            const double dx = std::max({x_lo - d.cx, 0.0, d.cx - x_hi});
            const double dy = std::max({y_lo - d.cy, 0.0, d.cy - y_hi});
            if (dx * dx + dy * dy <= d.radius * d.radius && d.cy - d.radius < y_hi) {
                row_out[c] = std::max(row_out[c], d.top_z);
            }
        }
    }
}

// Highest surface on the vertical line through each cell centre of row r.
void CentreOfRow(const Primitives& prims,
                 const RowBins& bins,
                 const core::GridGeometry& grid,
                 int r,
                 double* row_out) {
    const double x = grid.CellCenterX(r);
    for (const std::uint32_t i : bins.triangles[static_cast<std::size_t>(r)]) {
        const auto& v = prims.triangles[i].v;
        const Eigen::Vector2d a = v[0].head<2>();
        const Eigen::Vector2d e1 = v[1].head<2>() - a;
        const Eigen::Vector2d e2 = v[2].head<2>() - a;
        const double det = e1.x() * e2.y() - e1.y() * e2.x();
        if (det == 0.0) {
            continue;  // vertical triangle: a vertical line meets it in measure zero
        }
        int c0 = 0;
        int c1 = 0;
        CellRange(std::min({v[0].y(), v[1].y(), v[2].y()}) - 0.5 * grid.cell_m,
                  std::max({v[0].y(), v[1].y(), v[2].y()}) - 0.5 * grid.cell_m, grid.y0_m,
                  grid.cell_m, grid.cols, c0, c1);
        for (int c = std::max(0, c0); c <= std::min(grid.cols - 1, c1 + 1); ++c) {
            const Eigen::Vector2d q = Eigen::Vector2d(x, grid.CellCenterY(c)) - a;
            const double s = (q.x() * e2.y() - q.y() * e2.x()) / det;
            const double t = (e1.x() * q.y() - e1.y() * q.x()) / det;
            if (s >= 0.0 && t >= 0.0 && s + t <= 1.0) {
                const double z = v[0].z() + s * (v[1].z() - v[0].z()) + t * (v[2].z() - v[0].z());
                row_out[c] = std::max(row_out[c], z);
            }
        }
    }
    for (const std::uint32_t i : bins.discs[static_cast<std::size_t>(r)]) {
        const Disc& d = prims.discs[i];
        for (int c = 0; c < grid.cols; ++c) {
            const double dx = x - d.cx;
            const double dy = grid.CellCenterY(c) - d.cy;
            if (dx * dx + dy * dy <= d.radius * d.radius) {
                row_out[c] = std::max(row_out[c], d.top_z);
            }
        }
    }
}

}  // namespace

void GroundTruthOptions::Validate() const {
    const core::Check check("ground truth");
    check.Finite("datum_m", datum_m);
    check.That(cylinder_segments >= 8, "cylinder_segments", cylinder_segments, "allowed: >= 8");
}

bool ClampsToDatum(const core::Scene& scene, const GroundTruthOptions& options) {
    if (options.clamp_to_datum) {
        return *options.clamp_to_datum;
    }
    return std::none_of(scene.objects.begin(), scene.objects.end(),
                        [](const core::SceneObject& o) { return o.terrain; });
}

core::MapF GroundTruthElevation(const core::Scene& scene,
                                const core::GridGeometry& grid,
                                int threads) {
    return GroundTruthElevation(scene, grid, GroundTruthOptions{}, threads);
}

core::MapF GroundTruthElevation(const core::Scene& scene,
                                const core::GridGeometry& grid,
                                const GroundTruthOptions& options,
                                int threads) {
    grid.Validate();
    options.Validate();
    const Primitives prims = CollectPrimitives(scene, options.cylinder_segments);
    // The centre rule needs the rows whose centre line meets a primitive; binning by the
    // primitive's x extent is a superset of those.
    const RowBins bins = BinByRow(prims, grid);
    const bool clamp = ClampsToDatum(scene, options);
    core::MapF map(grid.rows, grid.cols, 0.0F);
    core::ParallelFor(static_cast<std::size_t>(grid.rows), threads, [&](std::size_t row) {
        const int r = static_cast<int>(row);
        std::vector<double> z(static_cast<std::size_t>(grid.cols), kNone);
        if (options.rule == TruthRule::kHighestInCell) {
            HighestInRow(prims, bins, grid, r, z.data());
        } else {
            CentreOfRow(prims, bins, grid, r, z.data());
        }
        for (int c = 0; c < grid.cols; ++c) {
            const double top = z[static_cast<std::size_t>(c)];
            const double value = top == kNone ? options.datum_m
                                 : clamp      ? std::max(options.datum_m, top)
                                              : top;
            map.at(r, c) = static_cast<float>(value);
        }
    });
    return map;
}

}  // namespace casmap::sim
