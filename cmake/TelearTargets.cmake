# Helpers shared by every layer: one place sets warnings and include roots.

# CMAKE_INSTALL_LIBDIR, CMAKE_INSTALL_INCLUDEDIR for every install() (cmake/TelearInstall.cmake).
include(GNUInstallDirs)

# telear_library(NAME SOURCES ... ) creates the static library telear_NAME, alias telear::NAME,
# whose public headers are included as "telear/NAME/file.hpp" from include/ (in the build
# tree and, installed, from the package's include directory). It is installed and exported
# as telear::NAME (find_package(telear)).
# Precompiled headers (issue 20): the third-party headers every unit of a layer parses through
# telear's own headers (Eigen everywhere; OpenCV from vision up; gRPC, protobuf and spdlog from
# net up; GoogleTest in the tests), parsed once per target instead of once per unit.
option(TELEAR_PCH "Precompile the heavy third-party headers of each target" ON)
# Unity builds of the libraries: their units instantiate the same Eigen, OpenCV and gRPC
# templates again and again (more than half of a core unit's compile time is template
# instantiation, which a precompiled header does not save); compiled in batches, each batch
# instantiates them once. File-local names are therefore unique within a library.
option(TELEAR_UNITY "Compile each library's sources in batches (CMake's UNITY_BUILD)" ON)
set(TELEAR_UNITY_BATCH_SIZE 8 CACHE STRING "sources per unity batch")
set(TELEAR_PCH_CORE <algorithm> <cmath> <functional> <map> <memory> <optional> <sstream> <string>
                    <vector> <Eigen/Core> <Eigen/Geometry>)
set(TELEAR_PCH_VISION ${TELEAR_PCH_CORE} <opencv2/core.hpp> <opencv2/imgproc.hpp>
                      <opencv2/calib3d.hpp>)
set(TELEAR_PCH_NET ${TELEAR_PCH_VISION} <grpcpp/grpcpp.h> <spdlog/spdlog.h>)
set(TELEAR_PCH_TEST <gtest/gtest.h> <gmock/gmock.h>)

# One precompiled header per level and kind, built once and reused by every target of that
# level (PRECOMPILE_HEADERS_REUSE_FROM): a holder object library per header set owns it. GCC
# accepts a precompiled header only where the macros it saw are defined the same way, so the
# holder has just the definitions the third-party headers themselves read (the imported
# targets' own, e.g. spdlog's), none of telear's (TELEAR_DEFAULT_DATA_DIR and the tests' paths
# appear in no precompiled header, so consumers may add them). Test holders compile at -O1
# like the test executables. One header per target instead cost ~300 CPU-s for 25 of them.
set(TELEAR_PCH_LINKS_CORE Eigen3::Eigen)
set(TELEAR_PCH_LINKS_VISION ${TELEAR_PCH_LINKS_CORE} opencv_core opencv_imgproc opencv_calib3d)
set(TELEAR_PCH_LINKS_NET ${TELEAR_PCH_LINKS_VISION} gRPC::grpc++ protobuf::libprotobuf
                         spdlog::spdlog)
function(telear_pch_holder level kind out)
  set(holder telear_pch_${level}_${kind})
  set(${out} ${holder} PARENT_SCOPE)
  if(TARGET ${holder})
    return()
  endif()
  string(TOUPPER ${level} upper)
  set(headers ${TELEAR_PCH_${upper}})
  add_library(${holder} OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch_holder.cpp)
  target_link_libraries(${holder} PRIVATE ${TELEAR_PCH_LINKS_${upper}})
  telear_warnings(${holder})
  if(kind STREQUAL "test")
    list(APPEND headers ${TELEAR_PCH_TEST})
    target_link_libraries(${holder} PRIVATE GTest::gtest GTest::gmock)
    telear_test_code(${holder})
  endif()
  target_precompile_headers(${holder} PRIVATE ${headers})
endfunction()

# telear_precompile(TARGET core|vision|net [test]): the header set of that level (and the
# GoogleTest headers for a test target), from its holder.
function(telear_precompile target level)
  if(NOT TELEAR_PCH)
    return()
  endif()
  set(kind lib)
  if(ARGN STREQUAL "test")
    set(kind test)
  endif()
  telear_pch_holder(${level} ${kind} holder)
  set_target_properties(${target} PROPERTIES PRECOMPILE_HEADERS_REUSE_FROM ${holder})
endfunction()

# Which header set a layer's units share (what its public headers include).
function(telear_pch_level name out)
  if(name MATCHES "^(core|geometry|sim_robot)$")
    set(${out} core PARENT_SCOPE)
  elseif(name MATCHES "^(vision|render|sim_rig)$")
    set(${out} vision PARENT_SCOPE)
  else()
    set(${out} net PARENT_SCOPE)
  endif()
endfunction()

# telear_library(NAME SOURCES ... ) creates the static library telear_NAME, alias telear::NAME,
# whose public headers are included as "telear/NAME/file.hpp" from include/ (in the build
# tree and, installed, from the package's include directory). It is installed and exported
# as telear::NAME (find_package(telear)).
#
# The AddressSanitizer tree (scripts/test.sh) compiles again only what it instruments -- the
# network layer, the simulated robot driver and the net tests -- and links the layers named in
# TELEAR_PREBUILT_LAYERS from the main tree's build in TELEAR_PREBUILT_DIR: such a library
# keeps its usage requirements (include paths, the packages it links) but its code is that
# tree's archive, compiled without instrumentation.
set(TELEAR_PREBUILT_DIR "" CACHE PATH "a build tree whose layer archives this tree links")
set(TELEAR_PREBUILT_LAYERS "" CACHE STRING "the layers linked from TELEAR_PREBUILT_DIR")
# telear_prebuilt_archive(NAME OUT): OUT is the main tree's libtelear_NAME.a when NAME is in
# TELEAR_PREBUILT_LAYERS (the same folder there as the current one here), else empty.
function(telear_prebuilt_archive name out)
  set(archive "")
  if(TELEAR_PREBUILT_DIR AND name IN_LIST TELEAR_PREBUILT_LAYERS)
    file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
    set(archive ${TELEAR_PREBUILT_DIR}/${folder}/libtelear_${name}.a)
    if(NOT EXISTS ${archive})
      message(FATAL_ERROR "TELEAR_PREBUILT_LAYERS: ${archive} is missing (build that tree first)")
    endif()
  endif()
  set(${out} ${archive} PARENT_SCOPE)
endfunction()

function(telear_library name)
  set(sources ${ARGN})
  telear_prebuilt_archive(${name} archive)
  if(archive)
    set(sources ${PROJECT_SOURCE_DIR}/cmake/prebuilt_layer.cpp)
  endif()
  add_library(telear_${name} STATIC ${sources})
  add_library(telear::${name} ALIAS telear_${name})
  set_target_properties(telear_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(telear_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                   $<INSTALL_INTERFACE:include>)
  if(archive)
    target_link_libraries(telear_${name} PUBLIC ${archive})
  else()
    telear_warnings(telear_${name})
    telear_pch_level(${name} level)
    telear_precompile(telear_${name} ${level})
    if(TELEAR_UNITY)
      set_target_properties(telear_${name} PROPERTIES UNITY_BUILD ON
                                                      UNITY_BUILD_BATCH_SIZE ${TELEAR_UNITY_BATCH_SIZE})
    endif()
  endif()
  # Every layer library is installed and exported (cmake/TelearInstall.cmake).
  set_property(GLOBAL APPEND PROPERTY TELEAR_EXPORTED_LIBRARIES telear_${name})
endfunction()

# telear_test_code(TARGET): a test executable or test helper library, compiled at -O1 in
# Release (see telear_test below); the test precompiled headers are built the same way.
function(telear_test_code target)
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

function(telear_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# telear_test(NAME SOURCES ... LIBS ... [PCH core|vision|net] [SYSTEM] [PROPERTIES ...])
# registers one GoogleTest executable per layer (or per kind of test in a layer) with CTest:
# every test case is its own CTest entry (gtest_discover_tests), so merging executables does
# not merge entries. Cases are listed when CTest runs (DISCOVERY_MODE PRE_TEST), not at build
# time. Each entry is labelled with its layer (the tests/ sub-folder), or LAYER-system for a
# SYSTEM executable (end-to-end runs of the simulator through servers or processes): `ctest -L`
# takes a regular expression, so `ctest -L net` runs one layer and `ctest -L system` the
# end-to-end tests. (One label each: gtest_discover_tests splits list-valued properties.)
#
# Test units are compiled at -O1 (the libraries they call stay at the build type's -O3): a
# test's own code is assertions and set-up, and -O3 code generation was a third of the CI's
# compile time (docs/development.md).
function(telear_test name)
  cmake_parse_arguments(T "SYSTEM" "PCH" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} telear::test_util GTest::gtest GTest::gmock
                                        GTest::gtest_main)
  telear_warnings(${name})
  telear_test_code(${name})
  if(NOT T_PCH)
    set(T_PCH core)
  endif()
  telear_precompile(${name} ${T_PCH} test)
  if(TELEAR_UNITY)
    # Test units are batched like the libraries' units: a test file's file-local helpers are
    # therefore unique within its executable, and shared ones live in tests/test_util or the
    # layer's helper files. (~40 % of the test units' compile time.)
    set_target_properties(${name} PROPERTIES UNITY_BUILD ON
                                             UNITY_BUILD_BATCH_SIZE ${TELEAR_UNITY_BATCH_SIZE})
  endif()
  get_filename_component(layer ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  set(label ${layer})
  set(cost "")
  if(T_SYSTEM)
    set(label ${layer}-system)
    # Started first: a clean clone has no CTest timing data, and a minute-long test started
    # last holds the whole run up while the other cores idle.
    set(cost COST 1000)
  endif()
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "TELEAR_DATA_DIR=${TELEAR_DATA_DIR}"
                                  LABELS ${label} ${cost} ${T_PROPERTIES})
endfunction()
