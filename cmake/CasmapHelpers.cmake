include(GNUInstallDirs)

# casmap_add_library(<module> SOURCES ... DEPS ...)
# One folder = one library target casmap_<module>, alias casmap::<module>. Headers are included
# as "casmap/<module>/<file>.hpp" both in the build tree and once installed: the build tree sees
# them through ${PROJECT_BINARY_DIR}/include/casmap/<module>, a link to the source folder.
function(casmap_add_library name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_library(casmap_${name} ${ARG_SOURCES})
    add_library(casmap::${name} ALIAS casmap_${name})
    file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/include/casmap)
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${name} ${PROJECT_BINARY_DIR}/include/casmap/${name}
        SYMBOLIC)
    target_include_directories(casmap_${name} PUBLIC
        $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_compile_features(casmap_${name} PUBLIC cxx_std_20)
    target_link_libraries(casmap_${name} PUBLIC ${ARG_DEPS})
    casmap_set_warnings(casmap_${name})
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
