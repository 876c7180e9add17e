# Mapper benchmarks: BM_MapperIngest (beams/s), BM_CasFilter vs BM_OpenCvMedian5 (200 x 200).
if(TARGET casmap::mapper)
    casmap_add_benchmark(mapper_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/mapper_bench.cpp
        DEPS casmap::mapper opencv_core opencv_imgproc)
endif()
# BM_ActiveWindowScan: the live window's per-scan update + row filter, p50/p99 per scan.
if(TARGET casmap::mapper)
    casmap_add_benchmark(active_window_bench
        SOURCES ${CMAKE_CURRENT_LIST_DIR}/active_window_bench.cpp DEPS casmap::mapper)
endif()
# Pre-filter precision/recall against simulated truth labels (reads run files: needs io).
if(TARGET casmap::mapper AND TARGET casmap::io)
    add_executable(prefilter_score ${CMAKE_CURRENT_LIST_DIR}/prefilter_score.cpp)
    target_link_libraries(prefilter_score PRIVATE casmap::mapper casmap::io)
endif()
# Mapper modes and CAS variants scored on simulated runs (reads run files: needs io).
if(TARGET casmap::mapper AND TARGET casmap::io)
    add_executable(variants_score ${CMAKE_CURRENT_LIST_DIR}/variants_score.cpp)
    target_link_libraries(variants_score PRIVATE casmap::mapper casmap::io)
endif()
