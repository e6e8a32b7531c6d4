# The version (docs/install.md): project(VERSION) in the top-level CMakeLists.txt, plus
# `git describe --always --dirty` taken at configure time when the source tree is a git
# checkout of its own (no git, a tarball, or a tree inside another repository: the project
# version alone). Both go into the generated header telear/core/version.hpp, written into
# the build tree's include directory (TELEAR_GENERATED_INCLUDE_DIR) and installed with the
# public headers. Re-run CMake to refresh the description after a commit.

set(TELEAR_GIT_DESCRIBE "")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --show-toplevel
                  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                  OUTPUT_VARIABLE telear_git_toplevel OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE telear_git_result ERROR_QUIET)
  file(REAL_PATH "${PROJECT_SOURCE_DIR}" telear_source_real)
  if(telear_git_result EQUAL 0 AND telear_git_toplevel)
    file(REAL_PATH "${telear_git_toplevel}" telear_git_toplevel)
  endif()
  if(telear_git_result EQUAL 0 AND telear_git_toplevel STREQUAL telear_source_real)
    execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty
                    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    OUTPUT_VARIABLE TELEAR_GIT_DESCRIBE OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE telear_git_result ERROR_QUIET)
    if(NOT telear_git_result EQUAL 0)
      set(TELEAR_GIT_DESCRIBE "")
    endif()
  endif()
endif()

if(TELEAR_GIT_DESCRIBE)
  set(TELEAR_VERSION_STRING "${PROJECT_VERSION} (${TELEAR_GIT_DESCRIBE})")
else()
  set(TELEAR_VERSION_STRING "${PROJECT_VERSION}")
endif()
message(STATUS "telear version: ${TELEAR_VERSION_STRING}")

set(TELEAR_GENERATED_INCLUDE_DIR "${PROJECT_BINARY_DIR}/include")
configure_file(${CMAKE_CURRENT_LIST_DIR}/version.hpp.in
               ${TELEAR_GENERATED_INCLUDE_DIR}/telear/core/version.hpp @ONLY)
