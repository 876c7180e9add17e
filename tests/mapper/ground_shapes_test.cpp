// The public functions of mapper/ground.hpp reject maps whose size differs from the elevation
// map's with an InputError naming the map, as CasFilter does (else they index one map by
// another's size), and LocalGroundEstimate a quantile outside 0..1 (it indexed past its window)
// or a negative k. The size mismatches are chosen in the direction the loops do not overrun.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/ground.hpp"

namespace casmap::mapper {
namespace {

// Runs `call`, expects an InputError whose field is `field`.
void ExpectRejected(const std::function<void()>& call, const std::string& field) {
    try {
        call();
        ADD_FAILURE() << "no InputError for " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

CasParams NanCas() {
    FilterParams params;
    params.Set("unknown", "nan");
    return params.cas;
}

TEST(GroundShapes, MapsOfAnotherSizeAreRejectedNamingTheMap) {
    const core::MapF h(4, 5, 0.1F);
    const core::MapF c(4, 5, 30.0F);
    const core::MapF larger(5, 6, 30.0F);
    const core::MapF smaller(3, 5, 0.1F);
    const CasParams cas = NanCas();
    FilterParams params;
    params.Set("unknown", "nan");

    ExpectRejected([&] { (void)LocalGroundEstimate(h, larger, 2, 0.5); }, "certainty");
    ExpectRejected([&] { (void)LocalGroundEstimate(h, c, 2, 1.5); }, "quantile");
    ExpectRejected([&] { (void)LocalGroundEstimate(h, c, -1, 0.5); }, "k");
    ExpectRejected(
        [&] {
            core::MapF out = larger;
            RestoreTrustedCells(h, c, cas, out);
        },
        "filtered");
    ExpectRejected(
        [&] {
            core::MapF out = h;
            RestoreTrustedCells(h, larger, cas, out);
        },
        "certainty");
    ExpectRejected(
        [&] {
            core::MapF out = larger;
            BoundByMeasurement(h, c, cas, out);
        },
        "filtered");
    ExpectRejected(
        [&] {
            core::MapF out = smaller;
            SmoothSurfaceCells(h, c, h, params, out);
        },
        "filtered");
    ExpectRejected(
        [&] {
            core::MapF out = h;
            SmoothSurfaceCells(h, c, larger, params, out);
        },
        "median");
    FilterResult cleaned;
    cleaned.elevation = smaller;
    cleaned.classes = ClassMap(3, 5, 0);
    ExpectRejected([&] { (void)GroundRelativeVotes(h, c, cas, cleaned); }, "cleaned.elevation");
    cleaned.elevation = h;
    ExpectRejected([&] { (void)GroundRelativeVotes(h, c, cas, cleaned); }, "cleaned.classes");
}

TEST(GroundShapes, SameSizeMapsAreAccepted) {
    const core::MapF h(4, 5, 0.1F);
    const core::MapF c(4, 5, 30.0F);
    const CasParams cas = NanCas();
    FilterParams params;
    params.Set("unknown", "nan");
    core::MapF out = h;
    EXPECT_NO_THROW(RestoreTrustedCells(h, c, cas, out));
    EXPECT_NO_THROW(BoundByMeasurement(h, c, cas, out));
    EXPECT_NO_THROW(SmoothSurfaceCells(h, c, h, params, out));
    FilterResult cleaned;
    cleaned.elevation = h;
    cleaned.classes = ClassMap(4, 5, 0);
    EXPECT_NO_THROW((void)GroundRelativeVotes(h, c, cas, cleaned));
    EXPECT_EQ(LocalGroundEstimate(h, c, 2, 0.5).data.size(), h.data.size());
}

}  // namespace
}  // namespace casmap::mapper
