include(GNUInstallDirs)

# casmap_add_library(<module> SOURCES ... DEPS ... [PRIVATE_HEADERS ...])
# One folder = one library target casmap_<module>, alias casmap::<module>. Headers are included
# as "casmap/<module>/<file>.hpp" both in the build tree and once installed: the build tree sees
# them through ${PROJECT_BINARY_DIR}/include/casmap/<module>, a link to the source folder.
# The library joins the export set casmapTargets (installed as casmap::<module>, see
# cmake/Install.cmake). Every <file>.hpp of the folder is installed to include/casmap/<module>/
# except PRIVATE_HEADERS (engine helpers that name HDF5, yaml-cpp, telegram internals) and the
# headers of a <file>.cpp left out of SOURCES (the simulator half in the robot build).
function(casmap_add_library name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_HEADERS" ${ARGN})
    add_library(casmap_${name} ${ARG_SOURCES})
    add_library(casmap::${name} ALIAS casmap_${name})
    set_target_properties(casmap_${name} PROPERTIES EXPORT_NAME ${name})
    file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/include/casmap)
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${name} ${PROJECT_BINARY_DIR}/include/casmap/${name}
        SYMBOLIC)
    target_include_directories(casmap_${name} PUBLIC
        $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_compile_features(casmap_${name} PUBLIC cxx_std_20)
    target_link_libraries(casmap_${name} PUBLIC ${ARG_DEPS})
    casmap_set_warnings(casmap_${name})

    set(sources)
    foreach(source IN LISTS ARG_SOURCES)
        get_filename_component(source_name ${source} NAME_WE)
        list(APPEND sources ${source_name})
    endforeach()
    file(GLOB headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${name}/*.hpp)
    set(public_headers)
    foreach(header IN LISTS headers)
        get_filename_component(header_file ${header} NAME)
        get_filename_component(header_name ${header} NAME_WE)
        if(header_file IN_LIST ARG_PRIVATE_HEADERS)
            continue()
        endif()
        if(EXISTS ${PROJECT_SOURCE_DIR}/${name}/${header_name}.cpp
           AND NOT header_name IN_LIST sources)
            continue()
        endif()
        list(APPEND public_headers ${header})
    endforeach()
    install(TARGETS casmap_${name} EXPORT casmapTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    install(FILES ${public_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/casmap/${name})
    set_property(GLOBAL APPEND PROPERTY CASMAP_LIBRARIES ${name})
endfunction()

function(casmap_set_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wconversion -Wshadow)
    if(CASMAP_WERROR)
        # -Wrestrict: GCC 12 false positive on std::string concatenation (GCC bug 105329).
        target_compile_options(${target} PRIVATE -Werror -Wno-error=restrict)
    endif()
endfunction()

# casmap_add_test(<name> SOURCES ... DEPS ...): one GoogleTest executable, tests discovered by CTest.
function(casmap_add_test name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
    target_compile_definitions(${name} PRIVATE
        CASMAP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
        CASMAP_BINARY_DIR="${PROJECT_BINARY_DIR}")
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
        PROPERTIES ENVIRONMENT "CASMAP_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()

if(CASMAP_SANITIZE)
    string(REPLACE ";" "," _casmap_san "${CASMAP_SANITIZE}")
    add_compile_options(-fsanitize=${_casmap_san} -fno-omit-frame-pointer)
    add_link_options(-fsanitize=${_casmap_san})
endif()
