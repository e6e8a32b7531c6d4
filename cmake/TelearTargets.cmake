# Helpers shared by every layer: one place sets warnings and include roots.

# CMAKE_INSTALL_LIBDIR, CMAKE_INSTALL_INCLUDEDIR for every install() (cmake/TelearInstall.cmake).
include(GNUInstallDirs)

# telear_library(NAME SOURCES ... ) creates the static library telear_NAME, alias telear::NAME,
# whose public headers are included as "telear/NAME/file.hpp" from include/ (in the build
# tree and, installed, from the package's include directory). It is installed and exported
# as telear::NAME (find_package(telear)).
function(telear_library name)
  add_library(telear_${name} STATIC ${ARGN})
  add_library(telear::${name} ALIAS telear_${name})
  set_target_properties(telear_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(telear_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                   $<INSTALL_INTERFACE:include>)
  telear_warnings(telear_${name})
  # Every layer library is installed and exported (cmake/TelearInstall.cmake).
  set_property(GLOBAL APPEND PROPERTY TELEAR_EXPORTED_LIBRARIES telear_${name})
endfunction()

function(telear_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# telear_test(NAME SOURCES ... LIBS ...) registers one GoogleTest executable with CTest.
function(telear_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} telear::test_util GTest::gtest GTest::gmock
                                        GTest::gtest_main)
  telear_warnings(${name})
  # Each test is labelled with its layer (the tests/ sub-folder), so `ctest -L net` runs one.
  get_filename_component(layer ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "TELEAR_DATA_DIR=${TELEAR_DATA_DIR}"
                                  LABELS ${layer})
endfunction()
