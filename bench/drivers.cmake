# LMS 200 telegram codec throughput (drivers_bench).
if(TARGET casmap::drivers)
    casmap_add_benchmark(drivers_bench SOURCES ${CMAKE_CURRENT_LIST_DIR}/drivers_bench.cpp DEPS casmap::drivers)
endif()
