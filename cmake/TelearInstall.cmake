# `cmake --install build --prefix PREFIX` (docs/install.md):
#   PREFIX/bin/telear
#   PREFIX/share/telear/data/          robots/, rigs/, cameras/ (core::data_directory() finds
#                                      them from the program: <bin>/../share/telear/data)
#   PREFIX/include/telear/<layer>/     the public headers, version.hpp (generated) and the
#                                      generated protobuf/gRPC headers in telear/v1/
#   PREFIX/<libdir>/libtelear_*.a      every layer library (telear_library()) and telear_proto
#   PREFIX/<libdir>/cmake/telear/      telearConfig.cmake, telearConfigVersion.cmake,
#                                      telearTargets.cmake: find_package(telear) gives
#                                      telear::core, ::geometry, ::vision, ::render, ::sim_robot, ::sim_rig,
#                                      ::proto, ::net, ::record_mcap, ::record_schemas_proto,
#                                      ::record_schemas, ::record, ::report, ::session, ::lab,
#                                      ::console
# bin/ and share/telear/data are fixed (not GNUInstallDirs' BINDIR / DATADIR) because
# data_directory() in src/core/robot_loader.cpp looks for the one relative to the other.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TELEAR_INSTALL_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/telear")
set(TELEAR_INSTALL_DATA_DIR "share/telear/data")

get_property(telear_exported_libraries GLOBAL PROPERTY TELEAR_EXPORTED_LIBRARIES)
# (Their INSTALL_INTERFACE include directory, set by telear_library(), is PREFIX/include.)
install(TARGETS ${telear_exported_libraries} EXPORT telearTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS telear RUNTIME DESTINATION bin)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/telear DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${TELEAR_GENERATED_INCLUDE_DIR}/telear/core/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/telear/core)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${TELEAR_INSTALL_DATA_DIR})

install(EXPORT telearTargets NAMESPACE telear:: DESTINATION ${TELEAR_INSTALL_CMAKE_DIR})
configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/telearConfig.cmake.in ${PROJECT_BINARY_DIR}/telearConfig.cmake
  INSTALL_DESTINATION ${TELEAR_INSTALL_CMAKE_DIR} PATH_VARS TELEAR_INSTALL_DATA_DIR)
# 0.x: a minor release may change the API (0.2.0 is the issue 11 restructure), so a
# request for 0.2 accepts 0.2.x only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/telearConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/telearConfig.cmake
              ${PROJECT_BINARY_DIR}/telearConfigVersion.cmake
        DESTINATION ${TELEAR_INSTALL_CMAKE_DIR})
