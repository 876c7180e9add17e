#include "casmap/mapper/synthetic_map.hpp"

#include <algorithm>
#include <cmath>

namespace casmap::mapper {
namespace {

// SplitMix64: a tiny generator whose output is the same on every platform and library.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t Next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31U);
    }
    double Uniform() { return static_cast<double>(Next() >> 11U) * 0x1.0p-53; }  // [0, 1)
    double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
    int Int(int lo, int hi) {  // [lo, hi]
        return lo + static_cast<int>(Next() % static_cast<std::uint64_t>(hi - lo + 1));
    }

private:
    std::uint64_t state_;
};

struct Box {
    int row0, col0, rows, cols;
    float height_m;
};

int Cells(double size_m, double cell_m) {
    return std::max(1, static_cast<int>(std::lround(size_m / cell_m)));
}

void Observe(SyntheticMap& m, int i, int j, float h, int hits, int a) {
    m.elevation.at(i, j) = h;
    m.certainty.at(i, j) = static_cast<float>(hits * a);
}

bool Inside(const SyntheticMap& m, int i, int j) {
    return i >= 0 && j >= 0 && i < m.truth.rows && j < m.truth.cols;
}

}  // namespace

SyntheticMap BuildSyntheticMap(const SyntheticMapConfig& cfg) {
    SyntheticMap m;
    m.grid.cell_m = cfg.cell_m;
    m.grid.rows = cfg.rows;
    m.grid.cols = cfg.cols;
    m.truth = core::MapF(cfg.rows, cfg.cols, 0.0F);
    m.elevation = core::MapF(cfg.rows, cfg.cols, 0.0F);
    m.certainty = core::MapF(cfg.rows, cfg.cols, 0.0F);
    Rng rng(cfg.seed);
    const double s = cfg.cell_m;
    const int rows = cfg.rows;
    const int cols = cfg.cols;

    // Truth: parallelepipeds #1, #2, #3 and the cylinder of Table I, positions as fractions
    // of the map so any size works.
    const std::vector<Box> boxes = {
        {rows * 20 / 100, cols * 15 / 100, Cells(0.530, s), Cells(0.559, s), 0.462F},
        {rows * 55 / 100, cols * 40 / 100, Cells(0.413, s), Cells(0.456, s), 0.414F},
        {rows * 25 / 100, cols * 60 / 100, Cells(0.400, s), Cells(0.343, s), 0.213F},
    };
    for (const Box& b : boxes) {
        for (int i = b.row0; i < b.row0 + b.rows; ++i) {
            for (int j = b.col0; j < b.col0 + b.cols; ++j) {
                if (Inside(m, i, j)) {
                    m.truth.at(i, j) = b.height_m;
                }
            }
        }
    }
    const double cyl_r = 0.411 / 2.0 / s;
    const double cyl_i = rows * 0.75;
    const double cyl_j = cols * 0.20;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            if (std::hypot(i + 0.5 - cyl_i, j + 0.5 - cyl_j) <= cyl_r) {
                m.truth.at(i, j) = 0.459F;
            }
        }
    }
    // Thin poles: one cell each (the highest point of a 2.5-24 mm pole falls in one cell).
    std::vector<std::pair<int, int>> poles;
    for (int p = 0; p < 9; ++p) {
        poles.emplace_back(rows * (10 + 9 * p) / 100, cols * (30 + 4 * (p % 3)) / 100);
    }
    for (const auto& [i, j] : poles) {
        m.truth.at(i, j) = 0.914F;
    }

    // Raw map. Coverage falls across-track: hits per cell 3..6 near, 0..2 beyond 55 % of the
    // columns (inside the paper's 80-column PI region, so its numbers see both regimes).
    const int sparse_from = cols * 55 / 100;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            // Sparse: 1/8 of the cells never seen, the rest seen once or twice.
            const int draw = rng.Int(0, 7);
            const int hits = j < sparse_from ? 3 + draw % 4 : (draw == 0 ? 0 : 1 + draw / 5);
            const auto noise = static_cast<float>(rng.Uniform(-0.004, 0.004));
            if (hits > 0) {
                Observe(m, i, j, m.truth.at(i, j) + noise, hits, cfg.a);
            }
        }
    }
    // Missing data: 12 % of each object top, plus occlusion shadows behind objects
    // (along +row, the direction of travel seen from the sensor's side).
    for (const Box& b : boxes) {
        for (int i = b.row0; i < b.row0 + b.rows; ++i) {
            for (int j = b.col0; j < b.col0 + b.cols; ++j) {
                if (Inside(m, i, j) && rng.Uniform() < 0.12) {
                    Observe(m, i, j, 0.0F, 0, cfg.a);
                }
            }
        }
        const int shadow = std::max(2, static_cast<int>(b.height_m / s / 3.0));
        for (int i = b.row0 + b.rows; i < b.row0 + b.rows + shadow; ++i) {
            for (int j = b.col0; j < b.col0 + b.cols; ++j) {
                if (Inside(m, i, j)) {
                    Observe(m, i, j, 0.0F, 0, cfg.a);
                }
            }
        }
        // Mixed pixels: streaks of intermediate heights in the shadow, seen once or twice.
        for (int j = b.col0; j < b.col0 + b.cols; ++j) {
            if (rng.Uniform() < 0.5) {
                const int i = b.row0 + b.rows + rng.Int(0, shadow - 1);
                if (Inside(m, i, j)) {
                    const auto h = static_cast<float>(b.height_m * rng.Uniform(0.1, 0.9));
                    Observe(m, i, j, h, rng.Int(1, 2), cfg.a);
                }
            }
        }
    }
    // Poles: seen on many scans (high certainty), with a mixed pixel behind each.
    for (const auto& [i, j] : poles) {
        Observe(m, i, j, 0.914F - static_cast<float>(rng.Uniform(0.0, 0.01)), 8, cfg.a);
        if (Inside(m, i + 2, j)) {
            Observe(m, i + 2, j, static_cast<float>(rng.Uniform(0.2, 0.7)), 1, cfg.a);
        }
    }
    // Random spikes (artifacts): isolated, seen once, anywhere.
    const int spikes = rows * cols / 500;
    for (int n = 0; n < spikes; ++n) {
        const int i = rng.Int(0, rows - 1);
        const int j = rng.Int(0, cols - 1);
        if (m.truth.at(i, j) == 0.0F) {
            Observe(m, i, j, static_cast<float>(rng.Uniform(0.1, 1.0)), 1, cfg.a);
        }
    }
    return m;
}

}  // namespace casmap::mapper
