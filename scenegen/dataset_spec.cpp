#include "casmap/scenegen/dataset_spec.hpp"

#include <cmath>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/scenegen/random.hpp"
#include "casmap/scenegen/scene_writer.hpp"

namespace casmap::scenegen {

void DatasetSpec::Validate(const std::string& where) const {
    const core::Check check(where);
    if (name.empty() || name.find_first_of("\n\r\"\\") != std::string::npos) {
        check.Fail("name", name, "must be non-empty, one line, without quotes or backslashes");
    }
    if (count < 0 || count > 10'000'000) {
        check.Fail("count", std::to_string(count), "allowed: 0..10000000");
    }
    if (!(train_fraction >= 0.0 && val_fraction >= 0.0 && train_fraction + val_fraction <= 1.0)) {
        check.Fail("splits", FormatNumber(train_fraction) + ", " + FormatNumber(val_fraction),
                   "train and val must be >= 0 with train + val <= 1 (test = the rest)");
    }
    if (!(region_length_m >= 0.5 && region_length_m <= 20.0)) {
        check.Fail("region.length_m", FormatNumber(region_length_m), "allowed: 0.5..20");
    }
    if (!(region_width_m >= 0.5 && region_width_m <= 10.0)) {
        check.Fail("region.width_m", FormatNumber(region_width_m), "allowed: 0.5..10");
    }
    if (!(region_start_x_m >= 0.5 && region_start_x_m <= 20.0)) {
        check.Fail("region.start_x_m", FormatNumber(region_start_x_m), "allowed: 0.5..20");
    }
    if (!(cell_m >= 0.005 && cell_m <= 0.5)) {
        check.Fail("region.cell_m", FormatNumber(cell_m), "allowed: 0.005..0.5");
    }
    if (outputs.pose_decimation < 1 || outputs.pose_decimation > 50) {
        check.Fail("outputs.pose_decimation", std::to_string(outputs.pose_decimation),
                   "allowed: 1..50 (poses at 1 kHz / n)");
    }
    scene.Validate(where);
    domain.Validate(where);
}

const char* SplitOf(const DatasetSpec& spec, std::uint64_t sample_seed) {
    Rng rng(SplitMix64(sample_seed ^ 0x5EED5EED5EED5EEDULL));
    const double u = rng.Uniform();
    if (u < spec.train_fraction) {
        return "train";
    }
    return u < spec.train_fraction + spec.val_fraction ? "val" : "test";
}

}  // namespace casmap::scenegen
