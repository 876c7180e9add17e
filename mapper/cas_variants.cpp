// The CAS filter's wave-2 forms (docs/paper-notes.md "Beyond the paper"). They reuse the
// paper's classification (cas_filter.cpp) on prepared inputs and post-process its classes:
// - unknown = nan: NaN cells enter as h = 0, c = 0 (never observed); removed cells become NaN
//   (unknown) instead of 0 (with ground = local a removed known cell takes the ground height);
//   the weighted median skips unknown cells; untouched NaN stays NaN.
// - ground = local (cas_terrain): Eq. 9's heights are h - g with g a low quantile of the
//   known heights around the cell, so a slope, a hill or a ditch is continuous as the flat
//   floor is (unknown cells keep relative height 0); a removed known cell takes the ground
//   height g (the paper's 0 is its floor's height), in either unknown convention; a filled cell
//   takes the weighted median of the actual heights.
// - support = height (cas_trail): a cell with 0 < c <= A is also removed when fewer than
//   support_min known window cells lie within support_tol_m of its height. A mixed-pixel
//   trail beside a pole has heights scattered between the pole's top and the floor, so few
//   neighbours share its height, while Eq. 10's window certainty is high there (the area is
//   well observed), which is why the paper's test keeps it. Floor, slopes and box tops (even
//   seen once) have many neighbours at their height; the pole's core has c > A and is never a
//   removal candidate.
#include "casmap/mapper/cas_variants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

namespace casmap::mapper::detail {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Weighted median of the Fig. 5 skeleton around (i, j) over `h`, leaving out cells with c = 0
// when `skip` (lower median, as skeleton_median.cpp); false when no sample is left.
bool SkeletonMedianAt(const core::MapF& h,
                      const core::MapF& c,
                      int i,
                      int j,
                      int k,
                      bool skip,
                      std::vector<float>& samples,
                      float& out) {
    samples.clear();
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            if (skip && c.at(i + di, j + dj) == 0.0F) {
                continue;
            }
            const std::size_t weight = std::abs(di) + std::abs(dj) <= 1 ? 1 : 2;
            samples.insert(samples.end(), weight, h.at(i + di, j + dj));
        }
    }
    if (samples.empty()) {
        return false;
    }
    const auto mid = samples.begin() + static_cast<std::ptrdiff_t>((samples.size() - 1) / 2);
    std::nth_element(samples.begin(), mid, samples.end());
    out = *mid;
    return true;
}

// Known (c > 0) cells of the window within tol of h(i, j), the centre excluded.
int HeightSupport(const core::MapF& h, const core::MapF& c, int i, int j, int k, float tol) {
    const float hc = h.at(i, j);
    int n = 0;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            if ((di != 0 || dj != 0) && c.at(i + di, j + dj) > 0.0F &&
                std::abs(h.at(i + di, j + dj) - hc) <= tol) {
                ++n;
            }
        }
    }
    return n;
}

}  // namespace

core::MapF LocalGround(const core::MapF& h, const core::MapF& c, int k, double quantile) {
    core::MapF g(h.rows, h.cols, 0.0F);
    std::vector<float> v;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            v.clear();
            for (int r = std::max(0, i - k); r <= std::min(h.rows - 1, i + k); ++r) {
                for (int s = std::max(0, j - k); s <= std::min(h.cols - 1, j + k); ++s) {
                    if (c.at(r, s) > 0.0F && !std::isnan(h.at(r, s))) {
                        v.push_back(h.at(r, s));
                    }
                }
            }
            if (v.empty()) {
                continue;
            }
            const auto at = static_cast<std::ptrdiff_t>(
                std::floor(quantile * static_cast<double>(v.size() - 1)));
            std::nth_element(v.begin(), v.begin() + at, v.end());
            g.at(i, j) = v[static_cast<std::size_t>(at)];
        }
    }
    return g;
}

void CasVariantInto(const core::MapF& h,
                    const core::MapF& c,
                    const CasParams& p,
                    FilterResult& out) {
    const bool nan = p.unknown == Unknown::kNaN;
    const bool local = p.ground == Ground::kLocal;
    // Unknown (NaN) cells enter as never observed: h = 0, c = 0.
    core::MapF h0 = h;
    core::MapF c0 = c;
    for (std::size_t n = 0; n < h0.data.size() && n < c0.data.size(); ++n) {
        if (std::isnan(h0.data[n])) {
            h0.data[n] = 0.0F;
            c0.data[n] = 0.0F;
        }
    }
    core::MapF ground;
    core::MapF base = h0;
    if (local) {
        ground = LocalGround(h0, c0, p.ground_k, p.ground_quantile);
        for (std::size_t n = 0; n < base.data.size(); ++n) {
            // Unknown cells stay at relative height 0, as they are at 0 in the paper's form.
            base.data[n] = c0.data[n] > 0.0F ? h0.data[n] - ground.data[n] : 0.0F;
        }
    }
    CasParams core_params = p;
    core_params.unknown = Unknown::kZero;
    core_params.ground = Ground::kZero;
    core_params.support = Support::kOff;
    if (nan) {
        core_params.wm_empty = WmEmpty::kSkip;  // a NaN has no place in a median
    }
    CasFilterInto(base, c0, core_params, out);  // the paper's classification
    const bool skip = core_params.wm_empty == WmEmpty::kSkip;
    const auto A = static_cast<float>(p.EffectiveA());
    const auto tol = static_cast<float>(p.support_tol_m);
    std::vector<float> samples;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            const std::size_t idx = static_cast<std::size_t>(i) * static_cast<std::size_t>(h.cols) +
                                    static_cast<std::size_t>(j);
            auto cls = static_cast<PixelClass>(out.classes.data[idx]);
            const float cij = c0.data[idx];
            if (p.support == Support::kHeight && cls == PixelClass::kUntouched && cij > 0.0F &&
                cij <= A && HeightSupport(h0, c0, i, j, p.k, tol) < p.support_min) {
                cls = PixelClass::kRemoved;
                out.classes.data[idx] = static_cast<std::uint8_t>(cls);
            }
            float& y = out.elevation.data[idx];
            if (cls == PixelClass::kRemoved) {
                // An unknown cell stays unknown; a known one takes the local ground (cas_terrain),
                // else the unknown value (the paper's 0, or NaN).
                const bool known = cij > 0.0F;
                y = known && local ? ground.data[idx] : (nan ? kNaN : 0.0F);
            } else if (cls == PixelClass::kFilled) {
                float m = 0.0F;
                if (SkeletonMedianAt(h0, c0, i, j, p.k, skip, samples, m)) {
                    y = m;
                } else {
                    y = nan ? kNaN : h.data[idx];
                }
            } else {
                y = h.data[idx];  // untouched or border: the input, NaN included
            }
        }
    }
}

}  // namespace casmap::mapper::detail
