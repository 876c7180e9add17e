#pragma once

// `casmap dataset` across processes with MPI (built when CASMAP_WITH_MPI and MPI are found):
// dynamic scheduling, rank 0 hands out sample indices as ranks finish (samples differ a lot in
// cost), every rank writes its own sample files (atomically, so a rank that dies leaves only
// finished samples behind), rank 0 collects the manifest lines and writes the index files.
// The samples and the manifest are byte-identical to a single-process run.

#include "casmap/pipeline/dataset.hpp"

namespace casmap::pipeline {

/// True when this build has MPI support.
[[nodiscard]] bool DatasetMpiBuilt();

/// True when this build has MPI and the process was started by an MPI launcher (mpirun,
/// mpiexec, srun: OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in the environment).
[[nodiscard]] bool LaunchedByMpi();

/// Where this process stands in a distributed run.
struct DistributedRole {
    int rank = 0;
    int ranks = 1;
};

/// Runs the dataset over every MPI rank (initialising and finalising MPI unless the caller
/// already did). Rank 0 runs `options.threads` local workers beside the scheduler; other ranks
/// generate one sample at a time. Shard options restrict the indices as in RunDataset.
/// `options.progress` is called on rank 0 only. Returns the summary on rank 0 (zeros
/// elsewhere) and sets `role`. Without MPI support: RunDataset.
[[nodiscard]] DatasetSummary RunDatasetDistributed(const scenegen::DatasetSpec& spec,
                                                   const DatasetContext& context,
                                                   const DatasetOptions& options,
                                                   DistributedRole& role);

}  // namespace casmap::pipeline
