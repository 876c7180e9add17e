# Simulator benchmarks (issue 3): BM_SimulateScan and BM_EmbreeRaw in one binary.
if(TARGET casmap::sim)
    casmap_add_benchmark(sim_bench SOURCES sim_bench.cpp DEPS casmap::sim casmap::io)
endif()
# End to end (issue 11): the `casmap simulate` path, stage by stage.
if(TARGET casmap::pipeline AND TARGET casmap::scenegen)
    casmap_add_benchmark(sim_e2e_bench SOURCES sim_e2e_bench.cpp
                         DEPS casmap::pipeline casmap::sim casmap::io casmap::scenegen)
endif()
