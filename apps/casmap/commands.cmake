# Each subcommand appends its source here (one line per command; keep sorted).
# list(APPEND CASMAP_APP_SOURCES filter_command.cpp)
# list(APPEND CASMAP_APP_SIM_SOURCES scan_command.cpp)
# list(APPEND CASMAP_APP_SIM_DEPS casmap::sim)
list(APPEND CASMAP_APP_SIM_SOURCES truth_command.cpp)
list(APPEND CASMAP_APP_SIM_DEPS casmap::sim)
list(APPEND CASMAP_APP_SIM_SOURCES scan_command.cpp)
list(APPEND CASMAP_APP_SIM_SOURCES mixed_pixels_command.cpp)
list(APPEND CASMAP_APP_SIM_DEPS casmap::sim)
