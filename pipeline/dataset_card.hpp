#pragma once

// The data card of a dataset: DIR/card.md (what varies, label statistics, mean PI per filter)
// and DIR/card/contact_sheet.png (truth, raw and CAS-filtered maps of the first samples).

#include <filesystem>
#include <vector>

#include "casmap/pipeline/dataset.hpp"

namespace casmap::pipeline {

/// Writes DIR/card.md and DIR/card/contact_sheet.png from the successful samples' records
/// (in index order), atomically.
void WriteDatasetCard(const scenegen::DatasetSpec& spec,
                      const std::filesystem::path& out_dir,
                      const std::vector<SampleRecord>& ok);

}  // namespace casmap::pipeline
