#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/mapper/consensus.hpp"
#include "casmap/mapper/kalman_noise.hpp"
#include "casmap/mapper/scan_filters.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/mapper/unknown.hpp"

namespace casmap::mapper {

/// The five filters of the paper's benchmark (Sec. III.A), then the wave-2 CAS variants
/// (docs/paper-notes.md "Beyond the paper"): cas_terrain (heights relative to a local ground
/// estimate) and cas_trail (removal also of low-certainty cells without support at their
/// own height: the mixed-pixel trail beside a pole), cas_median (cas_trail's kept objects at
/// their height, the median everywhere else), cas_edge (the median of cas_trail's output,
/// with objects and same-height surfaces such as box edges kept at their height), cas_hybrid
/// (cas_edge plus cas_median's surface rule for the cells cas_edge leaves at the median).
enum class FilterMethod {
    kCas,
    kWiener,
    kAverage,
    kMedian,
    kCwm,
    kCasTerrain,
    kCasTrail,
    kCasMedian,
    kCasEdge,
    kCasHybrid
};

/// "cas|wiener|average|median|cwm|cas_terrain|cas_trail|cas_median|cas_edge|cas_hybrid" ->
/// method; throws
/// InputError naming `field`.
[[nodiscard]] FilterMethod ParseFilterMethod(std::string_view name,
                                             const std::string& field = "method");
[[nodiscard]] std::string_view ToString(FilterMethod method);
/// The paper's five (the benchmark's columns); AllFilterMethodsWithVariants() adds the rest.
[[nodiscard]] const std::vector<FilterMethod>& AllFilterMethods();
[[nodiscard]] const std::vector<FilterMethod>& AllFilterMethodsWithVariants();

/// Eq. 9 form of the spatial-continuity test g_s.
enum class GsMode { kSum, kVariance };
/// What H-bar and C-bar are normalised by: the window's maximum or the whole map's.
enum class Normalise { kWindow, kGlobal };
/// Whether never-observed (c = 0) cells of the Fig. 5 skeleton enter the weighted median.
enum class WmEmpty { kInclude, kSkip };
/// What Eq. 9's heights are measured from: 0 m (the paper's flat floor) or a local ground
/// estimate (a low quantile of the observed heights around the cell): cas_terrain.
enum class Ground { kZero, kLocal };
/// Extra removal test (cas_trail): off, or remove cells with 0 < c <= A that have fewer than
/// support_min known window cells within support_tol_m of their own height.
enum class Support { kOff, kHeight };

/// CAS filter parameters (Eq. 7-10); defaults are the paper's values.
struct CasParams {
    int k = 2;                          // window (2k+1) x (2k+1)
    int a = 3;                          // Eq. 5 certainty increment, enters Eq. 8
    double cell_m = 0.025;              // Eq. 8 s
    double speed_m_s = 1.0;             // Eq. 8 v (the table's maximum)
    double scan_period_s = 1.0 / 75.0;  // Eq. 8 delta-t
    std::optional<double> A;            // Eq. 7 threshold; derived by Eq. 8 unless given
    std::optional<double> G;            // Eq. 10 window certainty sum; 10 A unless given
    GsMode gs_mode = GsMode::kSum;      // the paper's benchmark used the sum stand-in
    double h_sum_min = 7.0;             // g_s = 0 when the sum of H-bar < h_sum_min
    double B = 0.04;                    // Eq. 9 variance threshold (paper gives no value)
    Normalise normalise = Normalise::kWindow;
    bool e_term = false;                   // Eq. 10 sigma_c-bar > E term; the paper dropped it
    double E = 0.04;                       // Eq. 10
    WmEmpty wm_empty = WmEmpty::kInclude;  // Fig. 5 as printed: all 45 samples
    // --- wave 2 (docs/paper-notes.md "Beyond the paper"); defaults = the paper's filter ---
    Unknown unknown = Unknown::kZero;  // kNaN: NaN cells are unknown (removed -> NaN, never 0)
    Ground ground = Ground::kZero;     // kLocal for cas_terrain
    int ground_k = 4;                  // ground window (2 ground_k + 1)^2
    double ground_quantile = 0.5;      // quantile of the observed heights taken as ground
    Support support = Support::kOff;   // kHeight for cas_trail
    double support_tol_m = 0.05;       // "same height" (the spike threshold)
    int support_min = 5;               // known same-height window cells needed to keep a cell
    int edge_min = 7;                  // cas_edge: known same-height window cells of a surface
    double edge_tol_m = 0.06;          // cas_edge: "same height" of the surface test
    // cas_median's surface test: a known cell that stands out from the median by more than
    // support_tol_m but has at least surface_min known window cells (itself included) within
    // surface_tol_m of its height is on a surface (a box top at its edge or corner): it takes
    // the median of those cells instead of the plain median.
    double surface_tol_m = 0.015;
    int surface_min = 7;
    // cas_hybrid only: a surface cell takes B + c / (c + surface_prior) (h - B) (0: h, as
    // cas_edge); B = M + median_mix (median of the raw map - M) on non-object cells (0: M).
    double surface_prior = 0.0;
    double median_mix = 0.0;
    // cas_hybrid with unknown = nan only: median_mix's value there (< 0: median_mix itself). On
    // terrain a removed cell votes with the local ground in M, which the raw map's median R
    // does not need (docs/paper-notes.md "Median mix on terrain"); the paper's mode never reads it.
    double nan_median_mix = -1.0;
    [[nodiscard]] double EffectiveMedianMix() const {
        return unknown == Unknown::kNaN && nan_median_mix >= 0.0 ? nan_median_mix : median_mix;
    }
    // cas_hybrid only: a never-observed cell in the shadow beside a surface (box top) takes
    // edge_fill of the step up to it (0: off; docs/paper-notes.md "cas_hybrid").
    double edge_fill = 0.0;
    // ... and only beside a surface cell with at least edge_fill_run of its two neighbours
    // along the edge at its height (0: any; 1: the edge continues on one side at least).
    int edge_fill_run = 0;
    // cas_hybrid only: a box top's one-hit spill onto the floor beyond its far edge (0: off;
    // docs/paper-notes.md "cas_hybrid", "Spills"): a surface cell seen at most edge_spill_c times
    // whose far 4-neighbour and the cell beyond it are never observed, and whose measured height
    // lies at least edge_spill_drop_m below the median of the surface it continues, takes
    // edge_spill of the step down to the shadow's value, and no edge_fill grows from it.
    double edge_spill_c = 0.0;
    double edge_spill_drop_m = 0.01;
    double edge_spill = 0.0;

    /// Eq. 8: A = a * (round(s / (v dt)) + 2), or the given A.
    [[nodiscard]] double EffectiveA() const;
    /// G = 10 A unless given.
    [[nodiscard]] double EffectiveG() const;
};

/// Baseline filter parameters (Wiener, averaging, median, centre-weighted median).
struct BaselineParams {
    int window = 5;                    // odd side length of the square window
    std::optional<double> noise;       // Wiener noise power (m^2); mean local variance if unset
    int center_weight = 3;             // CWM: copies of the centre pixel (odd, so the count is odd)
    Unknown unknown = Unknown::kZero;  // kNaN: statistics over the window's known cells only
};

/// Every filter parameter, settable by name (NAME=VALUE; `casmap filter --set`, Python
/// keywords): the map filters' (CAS and its variants, the baselines) and the mapping stages' a
/// named pipeline may use: the scan pre-filters (shadow.<field>, range_jump.<field>,
/// sweep_jump.<field>), the Kalman mapper mode's noise model (kalman.<field>) and the consensus
/// mapper mode's cell height (consensus.<field>). A stage's
/// parameters matter only to pipelines that run the stage.
struct FilterParams {
    CasParams cas;
    BaselineParams baseline;
    ShadowFilterConfig shadow;   // shadow.min_angle_deg, .max_angle_deg, .window, .neighbors,
                                 // .remove_start_point
    RangeJumpConfig range_jump;  // range_jump.jump_min_m, .margin_m, .chord_tol_m
    SweepJumpConfig sweep_jump;  // sweep_jump.jump_min_m, .margin_m, .max_angle_deg
    KalmanNoiseConfig kalman;    // kalman.range_sigma_m, .beam_constant_m, .beam_angle_rad,
                                 // .min_variance_m2, .mahalanobis_gate, .multi_height_noise_m2
    ConsensusConfig consensus;   // consensus.spread_m, .min_hits

    /// Sets one parameter by name (`unknown` sets cas.unknown and baseline.unknown); throws
    /// InputError for an unknown name or a value out of range, "filter parameters: <name> =
    /// <value> (<rule>)" (a CLI shows "filter parameters" as its flag, e.g. --set).
    void Set(std::string_view name, std::string_view value);
    /// Parses "NAME=VALUE" and calls Set.
    void SetAssignment(std::string_view assignment);
    /// Throws InputError on inconsistent settings (cross-field rules such as range_jump.margin_m
    /// < range_jump.jump_min_m / 2 are checked here, not by Set, so the order of Set calls
    /// does not matter).
    void Validate() const;
    /// Names accepted by Set.
    [[nodiscard]] static const std::vector<std::string>& Names();
};

}  // namespace casmap::mapper
