#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {

FilterResult RunFilter(FilterMethod method,
                       const core::MapF& elevation,
                       const core::MapF& certainty,
                       const FilterParams& params) {
    params.Validate();
    switch (method) {
        case FilterMethod::kCas:
            return CasFilter(elevation, certainty, params.cas);
        case FilterMethod::kWiener:
            return FilterResult{WienerFilter(elevation, params.baseline), {}};
        case FilterMethod::kAverage:
            return FilterResult{AverageFilter(elevation, params.baseline), {}};
        case FilterMethod::kMedian:
            return FilterResult{MedianFilter(elevation, params.baseline), {}};
        case FilterMethod::kCwm:
            return FilterResult{CwmFilter(elevation, params.baseline), {}};
        case FilterMethod::kCasTerrain: {
            CasParams p = params.cas;
            p.ground = Ground::kLocal;
            return CasFilter(elevation, certainty, p);
        }
        case FilterMethod::kCasTrail: {
            CasParams p = params.cas;
            p.support = Support::kHeight;
            return CasFilter(elevation, certainty, p);
        }
        case FilterMethod::kCasMedian:
            return CasMedianFilter(elevation, certainty, params);
        case FilterMethod::kCasEdge:
            return CasEdgeFilter(elevation, certainty, params);
        case FilterMethod::kCasHybrid:
            return CasHybridFilter(elevation, certainty, params);
    }
    return {};
}

}  // namespace casmap::mapper
