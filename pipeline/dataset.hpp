#pragma once

// Synthetic datasets (`casmap dataset`; docs/commands/dataset.md): sample i of a spec is a pure
// function of (spec, i): seed(i) = scenegen::SampleSeed(spec.seed, i) -> a generated scene, a
// randomised rig and LMS 200 -> one simulated, mapped, filtered and scored run. Each sample
// lives in DIR/samples/NNNNNN/ (scene.yaml, ground.ply, rock meshes, rig.yaml, sensor.yaml,
// run.h5, files.sha256, sample.json written last); DIR/manifest.jsonl, DIR/dataset.yaml and
// DIR/card.md index them. Files are byte-identical whatever the thread count, rank count,
// shard or order of generation. Simulator builds only.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/pipeline/distributed.hpp"
#include "casmap/scenegen/dataset_spec.hpp"

namespace casmap::pipeline {

/// Where the rock meshes come from (scenes/meshes/rock_*.ply; empty: no rocks).
struct DatasetContext {
    std::filesystem::path out_dir;
    std::vector<std::filesystem::path> rock_meshes;
};

/// The rock meshes shipped with casmap: `dir`/rock_*.ply sorted by name, `dir` = the flag if
/// given, else ./scenes/meshes, else DataDir()/scenes/meshes. InputError naming "meshes_dir"
/// if none is found.
[[nodiscard]] std::vector<std::filesystem::path> FindRockMeshes(const std::string& dir_flag);

/// What one sample came to. `line` is its manifest line (JSON, no newline).
struct SampleRecord {
    std::size_t index = 0;
    bool ok = false;
    bool reused = false;  // found on disk with verified hashes
    std::string line;
};

/// DIR/samples/NNNNNN (six digits, more when needed).
[[nodiscard]] std::filesystem::path SampleDir(const std::filesystem::path& out_dir,
                                              std::size_t index);

/// Generates sample `index` into its directory (files written atomically, sample.json last)
/// and returns its record. A sample that cannot be generated (e.g. a scene the vehicle
/// cannot drive) returns ok = false with the error in its line; nothing throws for it.
[[nodiscard]] SampleRecord GenerateSample(const scenegen::DatasetSpec& spec,
                                          const DatasetContext& context,
                                          std::size_t index);

/// The record of a sample already on disk whose sample.json exists and whose files match
/// files.sha256; nullopt otherwise.
[[nodiscard]] std::optional<SampleRecord> VerifiedSample(const std::filesystem::path& out_dir,
                                                         std::size_t index);

/// GenerateSample unless VerifiedSample finds it (resume).
[[nodiscard]] SampleRecord ProduceSample(const scenegen::DatasetSpec& spec,
                                         const DatasetContext& context,
                                         std::size_t index);

/// Progress of a dataset run (for a terminal line: done, samples/s, ETA).
struct DatasetProgress {
    std::size_t done = 0;
    std::size_t total = 0;
    std::size_t failed = 0;
    double elapsed_s = 0.0;
};
using DatasetProgressFn = std::function<void(const DatasetProgress&)>;

/// Which indices this process generates: i % shards == shard.
struct DatasetOptions {
    int threads = 1;  // samples generated concurrently (each sample runs on one thread)
    std::size_t shard = 0;
    std::size_t shards = 1;
    DatasetProgressFn progress;  // called from worker threads, serialised

    /// threads >= 1, shards >= 1, shard < shards: InputError naming the field.
    void Validate() const;
};

/// "I/K" (0 <= I < K, whole numbers) -> options.shard = I, options.shards = K; InputError
/// naming `field` otherwise.
void ParseShard(std::string_view text, DatasetOptions& options, const std::string& field = "shard");

struct DatasetSummary {
    std::size_t generated = 0;
    std::size_t reused = 0;
    std::size_t failed = 0;
    std::size_t pending = 0;  // in other shards, not on disk yet
    double seconds = 0.0;
};

/// The indices of `shard` among `count`.
[[nodiscard]] std::vector<std::size_t> ShardIndices(std::size_t count,
                                                    std::size_t shard,
                                                    std::size_t shards);

/// Generates (or resumes) this shard's samples, then (rank 0) writes the index files
/// (WriteDatasetIndex) over every sample on disk. With a session of several MPI ranks, rank 0
/// hands out indices as ranks finish (distributed.hpp) and runs options.threads local workers;
/// each rank writes its own sample files (atomically: a rank that dies leaves only finished
/// samples). Otherwise options.threads threads. Returns the summary on rank 0, zeros elsewhere.
[[nodiscard]] DatasetSummary RunDataset(const scenegen::DatasetSpec& spec,
                                        const DatasetContext& context,
                                        const DatasetOptions& options,
                                        const DistributedSession& session);

/// RunDataset on local threads only.
[[nodiscard]] DatasetSummary RunDataset(const scenegen::DatasetSpec& spec,
                                        const DatasetContext& context,
                                        const DatasetOptions& options);

/// Writes DIR/manifest.jsonl (one line per index in order: this run's records, else a
/// verified sample on disk, else a "pending" line), DIR/dataset.yaml and DIR/card.md (with
/// DIR/card/contact_sheet.png), atomically. Returns the counts.
DatasetSummary WriteDatasetIndex(const scenegen::DatasetSpec& spec,
                                 const std::filesystem::path& out_dir,
                                 const std::map<std::size_t, SampleRecord>& records);

}  // namespace casmap::pipeline
