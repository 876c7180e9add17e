# The installed CMake package: `cmake --install build --prefix P` then, in a consumer,
# `find_package(casmap REQUIRED)` and `target_link_libraries(app PRIVATE casmap::pipeline)`.
# The libraries and their public headers are installed by casmap_add_library (CasmapHelpers);
# here: the export set, casmapConfig.cmake + version file, and the data (scenes/, config/)
# under share/casmap, where pipeline::DataDir() finds it from the installed program.
include(CMakePackageConfigHelpers)

set(CASMAP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/casmap)
install(EXPORT casmapTargets NAMESPACE casmap:: DESTINATION ${CASMAP_INSTALL_CMAKEDIR}
    FILE casmapTargets.cmake)

# Whether the simulator half (sensor_models, rig, sim) is in the package: the config file finds
# Embree, assimp and Bullet only then.
set(CASMAP_PACKAGE_WITH_SIM ${CASMAP_BUILD_SIM})
set(CASMAP_HDF5_LINK_LIBRARIES ${HDF5_C_LIBRARIES})
if(CASMAP_LIBDEFLATE_INCLUDE_DIR AND CASMAP_LIBDEFLATE_LIBRARY)
    list(APPEND CASMAP_HDF5_LINK_LIBRARIES ${CASMAP_LIBDEFLATE_LIBRARY})
endif()
# casmap::view (static) links cpp-httplib and nlohmann_json privately: the config file finds
# them when the view is in the package.
if(TARGET casmap_view)
    set(CASMAP_PACKAGE_WITH_VIEW ON)
else()
    set(CASMAP_PACKAGE_WITH_VIEW OFF)
endif()
if(CASMAP_BUILD_SIM AND CASMAP_WITH_MPI)
    set(CASMAP_PACKAGE_WITH_MPI ON)
    set(CASMAP_MPI_LINK_LIBRARIES ${MPI_C_LIBRARIES})
else()
    set(CASMAP_PACKAGE_WITH_MPI OFF)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/casmapConfig.cmake.in
    ${PROJECT_BINARY_DIR}/casmapConfig.cmake
    INSTALL_DESTINATION ${CASMAP_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/casmapConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/casmapConfig.cmake
              ${PROJECT_BINARY_DIR}/casmapConfigVersion.cmake
    DESTINATION ${CASMAP_INSTALL_CMAKEDIR})

install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes ${PROJECT_SOURCE_DIR}/config
    DESTINATION ${CMAKE_INSTALL_DATADIR}/casmap)
