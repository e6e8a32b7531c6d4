# ROS 1 (issue 21, docs/ros.md): Debian 12's roscpp, actionlib and message packages, found
# through pkg-config (no catkin, no setup.bash). TELEAR_WITH_ROS1 is on when they are all
# present; off, `telear robot-server --driver ros1` says it was not built.
#
# control_msgs is not packaged in Debian: its FollowJointTrajectory and GripperCommand actions
# are generated here, at build time, from their definitions in data/ros/control_msgs with
# Debian's own generators (actionlib_msgs' genaction, gencpp), so the headers carry the MD5
# sums real controllers check (the goal's: 69636787b6ecbde4d61d711979bc7ecb, asserted by
# tests/drivers). ROS 1 message headers do not compile as C++20, so everything that includes
# them is a C++17 target (src/drivers/ros1/CMakeLists.txt).

find_package(PkgConfig REQUIRED)
pkg_check_modules(TELEAR_ROS1_PKGS QUIET IMPORTED_TARGET
                  roscpp actionlib actionlib_msgs sensor_msgs trajectory_msgs visualization_msgs
                  std_msgs geometry_msgs)
set(TELEAR_ROS1_GENERATORS /usr/lib/actionlib_msgs/genaction.py /usr/lib/gencpp/gen_cpp.py)
set(TELEAR_ROS1_MSG_DIRS /usr/share/std_msgs/msg /usr/share/trajectory_msgs/msg
                         /usr/share/actionlib_msgs/msg)
set(telear_ros1_available OFF)
if(TELEAR_ROS1_PKGS_FOUND AND EXISTS /usr/bin/python3)
  set(telear_ros1_available ON)
  foreach(path IN LISTS TELEAR_ROS1_GENERATORS TELEAR_ROS1_MSG_DIRS)
    if(NOT EXISTS ${path})
      set(telear_ros1_available OFF)
    endif()
  endforeach()
endif()
option(TELEAR_WITH_ROS1 "Build the ROS 1 robot driver (roscpp, actionlib)" ${telear_ros1_available})
if(TELEAR_WITH_ROS1 AND NOT telear_ros1_available)
  message(FATAL_ERROR "TELEAR_WITH_ROS1 needs Debian's ROS 1 packages (scripts/install-deps.sh): "
                      "roscpp, actionlib, the message packages and their definitions, genmsg, "
                      "gencpp")
endif()
message(STATUS "telear: ROS 1 driver ${TELEAR_WITH_ROS1}")

# telear_ros1_generate_control_msgs(OUT_TARGET): an interface target whose include directory
# holds control_msgs/*.h, generated from data/ros/control_msgs.
function(telear_ros1_generate_control_msgs out_target)
  set(definitions ${PROJECT_SOURCE_DIR}/data/ros/control_msgs)
  set(msg_dir ${PROJECT_BINARY_DIR}/ros1/control_msgs/msg)
  set(include_dir ${PROJECT_BINARY_DIR}/ros1/include)
  set(actions FollowJointTrajectory GripperCommand)
  set(plain_messages JointTolerance GripperCommand)
  set(action_parts Action ActionGoal ActionResult ActionFeedback Goal Result Feedback)
  # The interpreter is Debian's: the scripts' `env python3` would find any other Python first.
  set(python /usr/bin/python3)
  set(search_paths -Icontrol_msgs:${msg_dir} -Istd_msgs:/usr/share/std_msgs/msg
                   -Itrajectory_msgs:/usr/share/trajectory_msgs/msg
                   -Iactionlib_msgs:/usr/share/actionlib_msgs/msg)
  set(all_headers)
  foreach(action IN LISTS actions)
    set(action_file ${definitions}/action/${action}.action)
    set(messages)
    foreach(part IN LISTS action_parts)
      list(APPEND messages ${msg_dir}/${action}${part}.msg)
    endforeach()
    add_custom_command(OUTPUT ${messages}
                       COMMAND ${python} /usr/lib/actionlib_msgs/genaction.py -o ${msg_dir}
                               ${action_file}
                       DEPENDS ${action_file}
                       COMMENT "control_msgs/${action}.action -> .msg (genaction)" VERBATIM)
    foreach(part IN LISTS action_parts)
      list(APPEND generated ${action}${part})
    endforeach()
  endforeach()
  foreach(message IN LISTS plain_messages)
    add_custom_command(OUTPUT ${msg_dir}/${message}.msg
                       COMMAND ${CMAKE_COMMAND} -E copy ${definitions}/msg/${message}.msg
                               ${msg_dir}/${message}.msg
                       DEPENDS ${definitions}/msg/${message}.msg VERBATIM)
    list(APPEND generated ${message})
  endforeach()
  set(all_messages)
  foreach(message IN LISTS generated)
    list(APPEND all_messages ${msg_dir}/${message}.msg)
  endforeach()
  # Each header depends on every .msg: a message's header embeds the definitions it uses.
  foreach(message IN LISTS generated)
    set(header ${include_dir}/control_msgs/${message}.h)
    add_custom_command(OUTPUT ${header}
                       COMMAND ${python} /usr/lib/gencpp/gen_cpp.py ${msg_dir}/${message}.msg
                               -p control_msgs ${search_paths} -o ${include_dir}/control_msgs
                               -e /usr/share/gencpp
                       DEPENDS ${all_messages} COMMENT "control_msgs/${message}.h (gencpp)"
                       VERBATIM)
    list(APPEND all_headers ${header})
  endforeach()
  add_custom_target(${out_target}_headers DEPENDS ${all_headers})
  add_library(${out_target} INTERFACE)
  target_include_directories(${out_target} SYSTEM INTERFACE ${include_dir})
  add_dependencies(${out_target} ${out_target}_headers)
endfunction()
