#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace casmap::mapper {

/// The five filters of the paper's benchmark (Sec. III.A).
enum class FilterMethod { kCas, kWiener, kAverage, kMedian, kCwm };

/// "cas|wiener|average|median|cwm" -> method; throws InputError naming `field`.
[[nodiscard]] FilterMethod ParseFilterMethod(std::string_view name,
                                             const std::string& field = "--method");
[[nodiscard]] std::string_view ToString(FilterMethod method);
[[nodiscard]] const std::vector<FilterMethod>& AllFilterMethods();

/// Eq. 9 form of the spatial-continuity test g_s.
enum class GsMode { kSum, kVariance };
/// What H-bar and C-bar are normalised by: the window's maximum or the whole map's.
enum class Normalise { kWindow, kGlobal };
/// Whether never-observed (c = 0) cells of the Fig. 5 skeleton enter the weighted median.
enum class WmEmpty { kInclude, kSkip };

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

    /// Eq. 8: A = a * (round(s / (v dt)) + 2), or the given A.
    [[nodiscard]] double EffectiveA() const;
    /// G = 10 A unless given.
    [[nodiscard]] double EffectiveG() const;
};

/// Baseline filter parameters (Wiener, averaging, median, centre-weighted median).
struct BaselineParams {
    int window = 5;               // odd side length of the square window
    std::optional<double> noise;  // Wiener noise power (m^2); mean local variance if unset
    int center_weight = 3;        // CWM: copies of the centre pixel (odd, so the count is odd)
};

/// Every filter parameter, settable by name (`--set NAME=VALUE`).
struct FilterParams {
    CasParams cas;
    BaselineParams baseline;

    /// Sets one parameter by name; throws InputError for an unknown name or a value out of
    /// range, naming "--set", the parameter, the value and the rule.
    void Set(std::string_view name, std::string_view value);
    /// Parses "NAME=VALUE" and calls Set.
    void SetAssignment(std::string_view assignment);
    /// Throws InputError on inconsistent settings.
    void Validate() const;
    /// Names accepted by Set.
    [[nodiscard]] static const std::vector<std::string>& Names();
};

}  // namespace casmap::mapper
