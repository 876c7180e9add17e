#include "casmap/mapper/stage_params.hpp"

#include <utility>

#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

StageParam Number(std::string key, double value) {
    return {std::move(key), core::FormatNumber(value)};
}

StageParam Integer(std::string key, int value) { return {std::move(key), std::to_string(value)}; }

StageParam OnOff(std::string key, bool on) { return {std::move(key), on ? "on" : "off"}; }

}  // namespace

std::vector<StageSection> StageSections(const FilterParams& params) {
    const ShadowFilterConfig& s = params.shadow;
    const RangeJumpConfig& r = params.range_jump;
    const SweepJumpConfig& w = params.sweep_jump;
    const KalmanNoiseConfig& k = params.kalman;
    const ConsensusConfig& c = params.consensus;
    return {
        {"shadow",
         {Number("min_angle_deg", s.min_angle_deg), Number("max_angle_deg", s.max_angle_deg),
          Integer("window", s.window), Integer("neighbors", s.neighbors),
          OnOff("remove_start_point", s.remove_start_point)}},
        {"range_jump",
         {Number("jump_min_m", r.jump_min_m), Number("margin_m", r.margin_m),
          Number("chord_tol_m", r.chord_tol_m)}},
        {"sweep_jump",
         {Number("jump_min_m", w.jump_min_m), Number("margin_m", w.margin_m),
          Number("max_angle_deg", w.max_angle_deg), Number("depression_share", w.depression_share),
          Integer("reach", w.reach)}},
        {"kalman",
         {Number("range_sigma_m", k.range_sigma_m), Number("beam_constant_m", k.beam_constant_m),
          Number("beam_angle_rad", k.beam_angle_rad), Number("min_variance_m2", k.min_variance_m2),
          Number("mahalanobis_gate", k.mahalanobis_gate),
          Number("multi_height_noise_m2", k.multi_height_noise_m2)}},
        {"consensus", {Number("spread_m", c.spread_m), Integer("min_hits", c.min_hits)}},
    };
}

}  // namespace casmap::mapper
