// Eq. 1-4 over a batch of beams (see beam_batch.hpp). Same formulas as terrain_mapper.cpp's
// scalar path (BeamZPartials, DeltaZMax, MotionBetween), rearranged so that every operation is
// element-wise arithmetic without calls: the rotation comes from the non-normalised quaternion
// with the factor 2 / |q|^2 (no square root), and the last row of the earlier rotation is
// used unscaled (the roll and pitch changes are angles between vectors, so any positive scale
// cancels). Four beams at a time with AVX2 where the CPU has it, else one at a time; both
// paths run the same IEEE operations in the same order (no FMA), so they give the same bits.
#include "casmap/mapper/beam_batch.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace casmap::mapper::detail {
namespace {

// The per-beam formulas, written once for a scalar double and for four AVX2 lanes (the same
// IEEE operations in the same order, no FMA: both give the same bits).
inline double Load(const double* p, double /*tag*/) { return *p; }
inline void Store(double* p, double v) { *p = v; }
inline double Sqrt(double a) { return std::sqrt(a); }
inline double Floor(double a) { return std::floor(a); }
inline double Abs(double a) { return std::fabs(a); }
inline double Max(double a, double b) { return a > b ? a : b; }
inline double Splat(double a, double /*tag*/) { return a; }
// 1 where the small-angle series is valid for atan2(y, x): x > 0 and |y| < 0.1 x.
inline double SeriesOk(double y, double x) { return x > 0.0 && std::fabs(y) < 0.1 * x ? 1.0 : 0.0; }

#if defined(__x86_64__) && defined(__GNUC__)
struct D4 {
    __m256d v;
};
#define CASMAP_AVX2 __attribute__((target("avx2"))) inline
CASMAP_AVX2 D4 Load(const double* p, D4 /*tag*/) { return {_mm256_loadu_pd(p)}; }
CASMAP_AVX2 void Store(double* p, D4 a) { _mm256_storeu_pd(p, a.v); }
CASMAP_AVX2 D4 operator+(D4 a, D4 b) { return {_mm256_add_pd(a.v, b.v)}; }
CASMAP_AVX2 D4 operator-(D4 a, D4 b) { return {_mm256_sub_pd(a.v, b.v)}; }
CASMAP_AVX2 D4 operator*(D4 a, D4 b) { return {_mm256_mul_pd(a.v, b.v)}; }
CASMAP_AVX2 D4 operator/(D4 a, D4 b) { return {_mm256_div_pd(a.v, b.v)}; }
CASMAP_AVX2 D4 operator-(D4 a) { return {_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0))}; }
CASMAP_AVX2 D4 Sqrt(D4 a) { return {_mm256_sqrt_pd(a.v)}; }
CASMAP_AVX2 D4 Floor(D4 a) { return {_mm256_floor_pd(a.v)}; }
CASMAP_AVX2 D4 Abs(D4 a) { return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)}; }
// a > b ? a : b, as the scalar Max (maxpd returns its second operand when unordered).
CASMAP_AVX2 D4 Max(D4 a, D4 b) {
    return {_mm256_blendv_pd(b.v, a.v, _mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ))};
}
CASMAP_AVX2 D4 Splat(double a, D4 /*tag*/) { return {_mm256_set1_pd(a)}; }
CASMAP_AVX2 D4 SeriesOk(D4 y, D4 x) {
    const __m256d pos = _mm256_cmp_pd(x.v, _mm256_setzero_pd(), _CMP_GT_OQ);
    const __m256d small =
        _mm256_cmp_pd(Abs(y).v, _mm256_mul_pd(_mm256_set1_pd(0.1), x.v), _CMP_LT_OQ);
    return {_mm256_and_pd(_mm256_and_pd(pos, small), _mm256_set1_pd(1.0))};
}
#undef CASMAP_AVX2
#endif

// atan(r) for |r| < 0.1 by its series (error < 1e-9 rad), as terrain_mapper.cpp's SmallAngle.
template <typename T>
inline T AtanSeries(T r) {
    const T one = Splat(1.0, r);
    const T r2 = r * r;
    return r * (one - r2 * (Splat(1.0 / 3.0, r) -
                            r2 * (Splat(1.0 / 5.0, r) -
                                  r2 * (Splat(1.0 / 7.0, r) - r2 / Splat(9.0, r)))));
}

// Eq. 1-4 for entry i (and the next lanes - 1 entries).
template <typename T>
inline void BeamAt(double delta_l_m, BeamBatch& b, std::size_t i, T tag) {
    const T one = Splat(1.0, tag);
    const T two = Splat(2.0, tag);
    const T qw = Load(&b.qw[i], tag);
    const T qx = Load(&b.qx[i], tag);
    const T qy = Load(&b.qy[i], tag);
    const T qz = Load(&b.qz[i], tag);
    // Rotation of q / |q| (Eigen's toRotationMatrix with 2 replaced by 2 / |q|^2).
    const T s = two / (((qw * qw + qx * qx) + qy * qy) + qz * qz);
    const T tx = s * qx;
    const T ty = s * qy;
    const T tz = s * qz;
    const T r00 = one - (ty * qy + tz * qz);
    const T r01 = ty * qx - tz * qw;
    const T r10 = ty * qx + tz * qw;
    const T r11 = one - (tx * qx + tz * qz);
    const T r20 = tz * qx - ty * qw;
    const T r21 = tz * qy + tx * qw;
    const T r22 = one - (tx * qx + ty * qy);
    // Eq. 1: world point.
    const T l = Load(&b.range_m[i], tag);
    const T ca = Load(&b.cos_a[i], tag);
    const T sa = Load(&b.sin_a[i], tag);
    const T lc = l * ca;
    const T ls = l * sa;
    Store(&b.x[i], (r00 * lc + r01 * ls) + Load(&b.ox[i], tag));
    Store(&b.y[i], (r10 * lc + r11 * ls) + Load(&b.oy[i], tag));
    Store(&b.z[i], (r20 * lc + r21 * ls) + Load(&b.oz[i], tag));
    // Last row of the earlier rotation, scaled by |q0|^2.
    const T pw = Load(&b.q0w[i], tag);
    const T px = Load(&b.q0x[i], tag);
    const T py = Load(&b.q0y[i], tag);
    const T pz = Load(&b.q0z[i], tag);
    const T bx = two * (px * pz - pw * py);
    const T by = two * (py * pz + pw * px);
    const T bz = ((pw * pw - px * px) - py * py) + pz * pz;
    // Roll change: the angle from (bz, by) to (r22, r21); pitch change: from (c0, -bx) to
    // (cp, -r20).
    const T roll_y = bz * r21 - by * r22;
    const T roll_x = bz * r22 + by * r21;
    const T tiny = Splat(1e-12, tag);
    const T c0 = Max(Sqrt(by * by + bz * bz), tiny);
    const T cp = Max(Sqrt(r21 * r21 + r22 * r22), tiny);
    const T pitch_y = bx * cp - c0 * r20;
    const T pitch_x = c0 * cp + bx * r20;
    Store(&b.redo[i], one - SeriesOk(roll_y, roll_x) * SeriesOk(pitch_y, pitch_x));
    const T d_roll = AtanSeries(roll_y / roll_x);
    const T d_pitch = AtanSeries(pitch_y / pitch_x);
    // Eq. 4 (DeltaZMax).
    const T inv_cp = one / cp;
    const T d_range = r20 * ca + r21 * sa;
    Store(&b.beam_z[i], d_range);
    const T d_roll_c = l * r22 * sa;
    const T d_pitch_c = -l * (cp * ca - r20 * r21 * inv_cp * sa);
    const T dx = Load(&b.dx[i], tag);
    const T dy = Load(&b.dy[i], tag);
    const T horizontal = Sqrt(dx * dx + dy * dy);
    Store(&b.dz_max[i], (((Abs(d_range) * Splat(delta_l_m, tag) + Abs(d_roll_c * d_roll)) +
                          Abs(d_pitch_c * d_pitch)) +
                         Abs(Load(&b.dz[i], tag))) +
                            horizontal * (Abs(r20) * inv_cp));
}

// Walks a trajectory with mostly increasing query times, so the per-beam pose lookup costs a
// few comparisons: a binary search at the first query of a scan (or after going backwards),
// then forward steps, so the cost per scan does not grow with the run's length. Position is
// interpolated linearly, orientation by linear interpolation of the quaternions (nlerp, left
// unnormalised: the kernel divides by |q|^2): between samples a few milliseconds apart it
// differs from Trajectory::PoseAt's slerp by far less than 1e-7 rad and needs no trigonometry.
class PoseCursor {
public:
    explicit PoseCursor(const core::Trajectory& trajectory) : samples_(trajectory.samples()) {}

    bool At(double t, Eigen::Vector4d& q_wxyz, Eigen::Vector3d& o) {
        if (samples_.empty() || !(t >= samples_.front().stamp_s) || t > samples_.back().stamp_s) {
            return false;
        }
        if (samples_.size() == 1) {
            const Eigen::Quaterniond& q = samples_.front().world_T_sensor.rotation;
            q_wxyz = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
            o = samples_.front().world_T_sensor.translation;
            return true;
        }
        if (!placed_ || t < samples_[k_].stamp_s) {
            Seek(t);
        }
        while (k_ + 2 < samples_.size() && samples_[k_ + 1].stamp_s <= t) {
            ++k_;
            inv_dt_ = 0.0;
        }
        const core::TimedPose& a = samples_[k_];
        const core::TimedPose& b = samples_[k_ + 1];
        if (inv_dt_ == 0.0) {
            inv_dt_ = 1.0 / (b.stamp_s - a.stamp_s);  // once per segment, not per beam
        }
        const double u = (t - a.stamp_s) * inv_dt_;
        o = a.world_T_sensor.translation +
            u * (b.world_T_sensor.translation - a.world_T_sensor.translation);
        const Eigen::Quaterniond& qa = a.world_T_sensor.rotation;
        const Eigen::Quaterniond& qb = b.world_T_sensor.rotation;
        const double sign = qa.dot(qb) < 0.0 ? -1.0 : 1.0;  // the shorter way round, as slerp
        const double ua = 1.0 - u;
        const double ub = u * sign;
        q_wxyz = Eigen::Vector4d(ua * qa.w() + ub * qb.w(), ua * qa.x() + ub * qb.x(),
                                 ua * qa.y() + ub * qb.y(), ua * qa.z() + ub * qb.z());
        return true;
    }

private:
    // k_ = the last sample at or before t, at most size - 2.
    void Seek(double t) {
        const auto after =
            std::upper_bound(samples_.begin(), samples_.end(), t,
                             [](double s, const core::TimedPose& p) { return s < p.stamp_s; });
        const auto before = static_cast<std::size_t>(after - samples_.begin());
        k_ = std::min(before == 0 ? 0 : before - 1, samples_.size() - 2);
        placed_ = true;
        inv_dt_ = 0.0;
    }

    const std::vector<core::TimedPose>& samples_;
    std::size_t k_ = 0;
    bool placed_ = false;
    double inv_dt_ = 0.0;
};

// atan2-based roll and pitch change for the entries the series does not cover.
void Redo(double delta_l_m, std::size_t i, BeamBatch& b) {
    const double s =
        2.0 / (b.qw[i] * b.qw[i] + b.qx[i] * b.qx[i] + b.qy[i] * b.qy[i] + b.qz[i] * b.qz[i]);
    const double r20 = s * (b.qx[i] * b.qz[i] - b.qw[i] * b.qy[i]);
    const double r21 = s * (b.qy[i] * b.qz[i] + b.qw[i] * b.qx[i]);
    const double r22 = 1.0 - s * (b.qx[i] * b.qx[i] + b.qy[i] * b.qy[i]);
    const double bx = 2.0 * (b.q0x[i] * b.q0z[i] - b.q0w[i] * b.q0y[i]);
    const double by = 2.0 * (b.q0y[i] * b.q0z[i] + b.q0w[i] * b.q0x[i]);
    const double bz =
        b.q0w[i] * b.q0w[i] - b.q0x[i] * b.q0x[i] - b.q0y[i] * b.q0y[i] + b.q0z[i] * b.q0z[i];
    const double d_roll = std::atan2(bz * r21 - by * r22, bz * r22 + by * r21);
    const double c0 = std::max(std::sqrt(by * by + bz * bz), 1e-12);
    const double cp = std::max(std::sqrt(r21 * r21 + r22 * r22), 1e-12);
    const double d_pitch = std::atan2(bx * cp - c0 * r20, c0 * cp + bx * r20);
    const double ca = b.cos_a[i];
    const double sa = b.sin_a[i];
    const double l = b.range_m[i];
    const double d_roll_c = l * r22 * sa;
    const double d_pitch_c = -l * (cp * ca - r20 * r21 / cp * sa);
    const double horizontal = std::sqrt(b.dx[i] * b.dx[i] + b.dy[i] * b.dy[i]);
    b.dz_max[i] = std::abs(r20 * ca + r21 * sa) * delta_l_m + std::abs(d_roll_c * d_roll) +
                  std::abs(d_pitch_c * d_pitch) + std::abs(b.dz[i]) +
                  horizontal * (std::abs(r20) / cp);
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"), flatten)) void KernelAvx2(double delta_l_m,
                                                         BeamBatch& b,
                                                         std::size_t n4) {
    for (std::size_t i = 0; i < n4; i += 4) {
        BeamAt(delta_l_m, b, i, D4{});
    }
}

bool HaveAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
    return avx2;
}
#endif

void Kernel(double delta_l_m, BeamBatch& b) {
    std::size_t i = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    if (HaveAvx2()) {
        i = b.size - b.size % 4;
        KernelAvx2(delta_l_m, b, i);
    }
#endif
    for (; i < b.size; ++i) {
        BeamAt(delta_l_m, b, i, 0.0);
    }
}

}  // namespace

void BeamBatch::Resize(std::size_t n) {
    for (std::vector<double>* v :
         {&qw, &qx,    &qy,    &qz,      &q0w, &q0x, &q0y, &q0z,    &ox,     &oy,   &oz,  &dx, &dy,
          &dz, &cos_a, &sin_a, &range_m, &x,   &y,   &z,   &dz_max, &beam_z, &redo, &row, &col}) {
        if (v->size() < n) {
            v->resize(n);
        }
    }
    if (beam.size() < n) {
        beam.resize(n);
    }
}

FillCounts FillBatch(const core::Scan& scan,
                     const core::Trajectory& world_T_sensor,
                     const BeamDirections& dirs,
                     double scan_period_s,
                     std::span<const std::uint8_t> keep,
                     BeamBatch& b) {
    const std::size_t n = scan.beams.size();
    FillCounts counts;
    b.size = 0;
    b.Resize(n);
    PoseCursor now(world_T_sensor);
    PoseCursor before(world_T_sensor);
    const double start_s = world_T_sensor.empty() ? 0.0 : world_T_sensor.StartTime();
    Eigen::Vector4d q = Eigen::Vector4d::Zero();
    Eigen::Vector4d q0 = Eigen::Vector4d::Zero();
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
    Eigen::Vector3d o0 = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const core::Beam& beam = scan.beams[i];
        if (beam.status != core::BeamStatus::kOk) {
            ++counts.not_ok;
            continue;
        }
        if (!keep.empty() && keep[i] == 0) {
            ++counts.rejected;
            continue;
        }
        const double t = scan.BeamTime(i);
        if (!now.At(t, q, o)) {
            ++counts.no_pose;
            continue;
        }
        // The previous measurement was one scan period earlier; before the trajectory starts,
        // the motion since its start stands in (zero at the very first pose).
        before.At(std::max(t - scan_period_s, start_s), q0, o0);
        const std::size_t j = b.size++;
        b.beam[j] = static_cast<std::uint32_t>(i);
        b.qw[j] = q[0];
        b.qx[j] = q[1];
        b.qy[j] = q[2];
        b.qz[j] = q[3];
        b.q0w[j] = q0[0];
        b.q0x[j] = q0[1];
        b.q0y[j] = q0[2];
        b.q0z[j] = q0[3];
        b.ox[j] = o.x();
        b.oy[j] = o.y();
        b.oz[j] = o.z();
        b.dx[j] = o.x() - o0.x();
        b.dy[j] = o.y() - o0.y();
        b.dz[j] = o.z() - o0.z();
        b.cos_a[j] = dirs.cos[i];
        b.sin_a[j] = dirs.sin[i];
        b.range_m[j] = static_cast<double>(beam.range_m);
    }
    return counts;
}

namespace {

// Grid cells of the batch's points: GridGeometry::CellOf's floor((x - x0) / s), vectorised.
template <typename T>
inline void CellAt(const core::GridGeometry& g, BeamBatch& b, std::size_t i, T tag) {
    const T s = Splat(g.cell_m, tag);
    Store(&b.row[i], Floor((Load(&b.x[i], tag) - Splat(g.x0_m, tag)) / s));
    Store(&b.col[i], Floor((Load(&b.y[i], tag) - Splat(g.y0_m, tag)) / s));
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"), flatten)) void CellsAvx2(const core::GridGeometry& g,
                                                        BeamBatch& b,
                                                        std::size_t n4) {
    for (std::size_t i = 0; i < n4; i += 4) {
        CellAt(g, b, i, D4{});
    }
}
#endif

void Cells(const core::GridGeometry& g, BeamBatch& b) {
    std::size_t i = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    if (HaveAvx2()) {
        i = b.size - b.size % 4;
        CellsAvx2(g, b, i);
    }
#endif
    for (; i < b.size; ++i) {
        CellAt(g, b, i, 0.0);
    }
}

}  // namespace

void ComputeBatch(double delta_l_m, BeamBatch& batch, const core::GridGeometry* grid) {
    Kernel(delta_l_m, batch);
    for (std::size_t i = 0; i < batch.size; ++i) {
        if (batch.redo[i] != 0.0) {
            Redo(delta_l_m, i, batch);
        }
    }
    if (grid != nullptr) {
        Cells(*grid, batch);
    }
}

}  // namespace casmap::mapper::detail
