# Simulator benchmarks (issue 3): BM_SimulateScan and BM_EmbreeRaw in one binary.
if(TARGET casmap::sim)
    casmap_add_benchmark(sim_bench SOURCES sim_bench.cpp DEPS casmap::sim casmap::io)
endif()
