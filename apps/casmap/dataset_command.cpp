// casmap dataset --spec SPEC.yaml --out DIR [--count N] [--seed S] [--shard I/K] [--threads T]
//                [--meshes DIR]
// A synthetic dataset (docs/commands/dataset.md): procedural scenes, randomised rig and
// sensor, one run file per sample, DIR/manifest.jsonl, DIR/dataset.yaml, DIR/card.md. The same
// command under `mpirun -n K` spreads the samples over K ranks. Reruns resume. Exit status 0
// when every sample succeeded, 64 + min(failed, 60) when some failed, 2 for bad input.
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/dataset_spec_file.hpp"
#include "casmap/pipeline/dataset.hpp"
#include "casmap/pipeline/distributed.hpp"

namespace casmap::app {
namespace {

struct DatasetFlags {
    std::string spec;
    std::string out;
    std::string shard;  // I/K
    std::string meshes;
    int count = -1;
    std::uint64_t seed = 0;
};

// One status line on a terminal: samples done, samples/s, ETA.
void DrawProgress(const pipeline::DatasetProgress& p) {
    if (isatty(STDERR_FILENO) == 0) {
        return;
    }
    const double rate = p.elapsed_s > 0.0 ? static_cast<double>(p.done) / p.elapsed_s : 0.0;
    const double eta = rate > 0.0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
    std::fprintf(stderr, "\rdataset: %zu/%zu samples (%zu failed), %.2f samples/s, ETA %.0f s   ",
                 p.done, p.total, p.failed, rate, eta);
    if (p.done == p.total) {
        std::fprintf(stderr, "\n");
    }
}

void RunDatasetCommand(const DatasetFlags& flags, const CommonOptions& common, bool seed_given) {
    scenegen::DatasetSpec spec = io::LoadDatasetSpec(flags.spec);
    if (flags.count >= 0) {
        spec.count = flags.count;
    }
    if (seed_given) {
        spec.seed = flags.seed;
    }
    spec.Validate(flags.spec);
    pipeline::DatasetOptions options;
    if (!flags.shard.empty()) {
        WithFlagNames({{"shard", "--shard"}}, [&] { pipeline::ParseShard(flags.shard, options); });
    }
    options.threads = core::ResolveThreads(common.threads);
    options.progress = DrawProgress;
    pipeline::DatasetContext context;
    context.out_dir = flags.out;
    WithFlagNames({{"meshes_dir", "--meshes"}},
                  [&] { context.rock_meshes = pipeline::FindRockMeshes(flags.meshes); });
    const pipeline::DistributedSession session;  // MPI when started by mpirun/srun, else one rank
    if (session.rank() == 0) {
        io::EnsureDirectory(context.out_dir);
    }
    const pipeline::DatasetSummary s = pipeline::RunDataset(spec, context, options, session);
    if (session.rank() != 0) {
        return;
    }
    std::printf(
        "dataset %s: %d samples -> %s (%zu generated, %zu reused, %zu failed, %zu pending in "
        "other shards) in %.1f s on %d rank(s)\n",
        spec.name.c_str(), spec.count, flags.out.c_str(), s.generated, s.reused, s.failed,
        s.pending, s.seconds, session.ranks());
    if (s.failed > 0) {
        std::fprintf(stderr, "casmap: %zu sample(s) failed; see status \"failed\" in %s\n",
                     s.failed, (context.out_dir / "manifest.jsonl").c_str());
        throw CLI::RuntimeError(64 + static_cast<int>(std::min<std::size_t>(s.failed, 60)));
    }
}

}  // namespace

void AddDatasetCommand(CLI::App& app, CommonOptions& common) {
    auto flags = std::make_shared<DatasetFlags>();
    CLI::App* sub = app.add_subcommand(
        "dataset", "Generate a synthetic dataset (procedural scenes, randomised rig and sensor)");
    sub->add_option("--spec", flags->spec, "dataset spec YAML (config/datasets/default.yaml)")
        ->required();
    sub->add_option("--out", flags->out, "output directory")->required();
    sub->add_option("--count", flags->count, "number of samples (overrides the spec)")
        ->check(WholeNumberCheck(0, 100000000));
    CLI::Option* seed = sub->add_option("--seed", flags->seed, "dataset seed (overrides the spec)");
    sub->add_option("--shard", flags->shard, "generate only indices i with i % K == I (I/K)");
    sub->add_option("--meshes", flags->meshes, "directory of rock_*.ply meshes (scenes/meshes)");
    AddThreadsOption(sub, common);
    sub->callback([flags, seed, &common] { RunDatasetCommand(*flags, common, seed->count() > 0); });
}

}  // namespace casmap::app
