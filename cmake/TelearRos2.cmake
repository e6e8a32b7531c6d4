# ROS 2 over DDS (issue 21, docs/ros2.md): Debian 12 has no rclcpp, but it has Eclipse Cyclone
# DDS 0.10 (cyclonedds-dev, the C API) and its IDL compiler (cyclonedds-tools' idlc), the DDS
# that rmw_cyclonedds_cpp runs ROS 2 on. TELEAR_WITH_ROS2 is on when both are present; off,
# `telear robot-server --driver ros2` says it was not built.
#
# The ROS 2 message types the driver uses are written as IDL in data/ros2/idl, in the layout
# and with the names rosidl_generator_dds_idl gives them (sensor_msgs/msg/dds_/JointState_.idl,
# type sensor_msgs::msg::dds_::JointState_), and compiled to C here, at build time, by Debian's
# idlc:
#   - final extensibility (idlc's default, said explicitly): plain CDR, as ROS 2 writes it;
#   - no XTypes type information (NO_TYPE_INFO): rmw_cyclonedds registers its types without
#     any ("not yet providing type discovery, assignability checking", its serdata.cpp), so a
#     ROS 2 node and telear match on the type name alone, as two ROS 2 nodes do.

find_package(CycloneDDS CONFIG QUIET)
find_program(TELEAR_IDLC idlc)
set(telear_ros2_available OFF)
if(CycloneDDS_FOUND AND TARGET CycloneDDS::ddsc AND TELEAR_IDLC)
  set(telear_ros2_available ON)
endif()
option(TELEAR_WITH_ROS2 "Build the ROS 2 robot driver (Cyclone DDS, idlc)" ${telear_ros2_available})
if(TELEAR_WITH_ROS2 AND NOT telear_ros2_available)
  message(FATAL_ERROR "TELEAR_WITH_ROS2 needs Debian's cyclonedds-dev and cyclonedds-tools "
                      "(idlc): scripts/install-deps.sh")
endif()
message(STATUS "telear: ROS 2 driver ${TELEAR_WITH_ROS2}")
if(TELEAR_WITH_ROS2)
  # idlc writes C; the rest of telear is C++ only.
  enable_language(C)
endif()

# The IDL, relative to data/ros2/idl (dependencies first, for the reader).
set(TELEAR_ROS2_IDL
    builtin_interfaces/msg/dds_/Time_.idl builtin_interfaces/msg/dds_/Duration_.idl
    std_msgs/msg/dds_/Header_.idl sensor_msgs/msg/dds_/JointState_.idl
    trajectory_msgs/msg/dds_/JointTrajectoryPoint_.idl
    trajectory_msgs/msg/dds_/JointTrajectory_.idl)

# telear_ros2_generate_messages(OUT_TARGET): a static C library of the generated types (their
# topic descriptors, e.g. sensor_msgs_msg_dds__JointState__desc) whose include directory holds
# the generated headers (#include "sensor_msgs/msg/dds_/JointState_.h"); links Cyclone DDS.
function(telear_ros2_generate_messages out_target)
  set(idl_dir ${PROJECT_SOURCE_DIR}/data/ros2/idl)
  set(files)
  foreach(idl IN LISTS TELEAR_ROS2_IDL)
    list(APPEND files ${idl_dir}/${idl})
  endforeach()
  # idlc_generate (CycloneDDS's Generate.cmake) writes into the calling directory's binary
  # folder, mirroring data/ros2/idl below it (BASE_DIR), and gives an interface target whose
  # sources are the generated .c files; a static library of its own compiles them once.
  idlc_generate(TARGET ${out_target}_idl FILES ${files} BASE_DIR ${idl_dir} INCLUDES ${idl_dir}
                DEFAULT_EXTENSIBILITY final NO_TYPE_INFO)
  add_library(${out_target} STATIC)
  target_link_libraries(${out_target} PRIVATE ${out_target}_idl PUBLIC CycloneDDS::ddsc)
  # SYSTEM: the generated headers are not telear's to keep warning-free under -Wpedantic.
  target_include_directories(${out_target} SYSTEM PUBLIC ${CMAKE_CURRENT_BINARY_DIR})
  set_target_properties(${out_target} PROPERTIES C_STANDARD 99 POSITION_INDEPENDENT_CODE ON)
endfunction()
