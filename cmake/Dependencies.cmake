# find_package() only for what the enabled modules need.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Threads REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
find_package(yaml-cpp REQUIRED)
find_package(HDF5 REQUIRED COMPONENTS C)

# HDF5's C API as one imported target.
if(NOT TARGET casmap::hdf5)
    add_library(casmap::hdf5 INTERFACE IMPORTED)
    target_include_directories(casmap::hdf5 INTERFACE ${HDF5_INCLUDE_DIRS})
    target_link_libraries(casmap::hdf5 INTERFACE ${HDF5_C_LIBRARIES})
    target_compile_definitions(casmap::hdf5 INTERFACE ${HDF5_DEFINITIONS})
    # libdeflate (optional, Debian libdeflate-dev): io compresses the chunks of the noisy datasets
    # it writes with it (about twice as fast as zlib) into the zlib stream HDF5's deflate filter
    # reads, and takes Adler-32 from it (io/hdf5_chunk_writer.cpp, io/deflate_stream.cpp). Part of this
    # wrapper: only the HDF5 writer uses it.
    find_path(CASMAP_LIBDEFLATE_INCLUDE_DIR libdeflate.h)
    find_library(CASMAP_LIBDEFLATE_LIBRARY deflate)
    if(CASMAP_LIBDEFLATE_INCLUDE_DIR AND CASMAP_LIBDEFLATE_LIBRARY)
        target_include_directories(casmap::hdf5 INTERFACE ${CASMAP_LIBDEFLATE_INCLUDE_DIR})
        target_link_libraries(casmap::hdf5 INTERFACE ${CASMAP_LIBDEFLATE_LIBRARY})
        target_compile_definitions(casmap::hdf5 INTERFACE CASMAP_HAVE_LIBDEFLATE=1)
    else()
        message(STATUS "casmap: libdeflate not found, HDF5 chunks are compressed by casmap's encoder")
    endif()
endif()

# yaml-cpp 0.7 on Debian 12 exports target "yaml-cpp".
if(NOT TARGET yaml-cpp::yaml-cpp)
    add_library(yaml-cpp::yaml-cpp INTERFACE IMPORTED)
    target_link_libraries(yaml-cpp::yaml-cpp INTERFACE yaml-cpp)
endif()

if(CASMAP_BUILD_SIM)
    find_package(embree 3 REQUIRED)
    find_package(assimp REQUIRED)
    find_package(Bullet REQUIRED)
    # Bullet ships variables only: wrap them once. Debian builds Bullet in single precision.
    if(NOT TARGET casmap::bullet)
        add_library(casmap::bullet INTERFACE IMPORTED)
        target_include_directories(casmap::bullet SYSTEM INTERFACE ${BULLET_INCLUDE_DIRS})
        target_link_libraries(casmap::bullet INTERFACE ${BULLET_LIBRARIES})
        target_compile_definitions(casmap::bullet INTERFACE ${BULLET_DEFINITIONS})
    endif()
endif()

# MPI for `casmap dataset` across machines: optional, the command falls back to threads.
if(CASMAP_WITH_MPI AND CASMAP_BUILD_SIM)
    find_package(MPI COMPONENTS C)
    if(NOT MPI_C_FOUND)
        message(STATUS "casmap: MPI not found, casmap dataset runs on threads only")
        set(CASMAP_WITH_MPI OFF)
    endif()
endif()

if(CASMAP_BUILD_VIEW)
    # cpp-httplib (Debian: libcpp-httplib-dev) as a compiled library with its pkg-config flags.
    find_package(PkgConfig REQUIRED)
    pkg_check_modules(httplib REQUIRED IMPORTED_TARGET cpp-httplib)
    find_package(nlohmann_json 3 REQUIRED)
endif()

if(CASMAP_BUILD_TESTS)
    find_package(GTest REQUIRED)
    include(GoogleTest)
endif()
if(CASMAP_BUILD_BENCHMARKS)
    find_package(benchmark REQUIRED)
endif()
