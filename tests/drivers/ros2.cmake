# drivers: the ROS 2 driver against a Cyclone DDS peer (docs/ros2.md): ros2_test_peer.cpp plays a
# ros2_control arm (joint_state_broadcaster + a JointTrajectoryController's topic) with the types
# generated from data/ros2/idl, `telear robot-server --driver ros2` driven over gRPC. Discovery
# stays on loopback (unicast to 127.0.0.1, no multicast: ros2_harness.py's CYCLONEDDS_URI) on a
# domain of each test's own, so the cases may run beside each other and beside other DDS users.
if(NOT TELEAR_WITH_ROS2)
  return()
endif()

add_executable(ros2_test_peer ${CMAKE_CURRENT_LIST_DIR}/ros2_test_peer.cpp)
target_link_libraries(ros2_test_peer PRIVATE telear_ros2_msgs)
telear_warnings(ros2_test_peer)
telear_test_code(ros2_test_peer)

# One CTest entry per test case (unittest names).
set(ros2_driver_cases
  test_types_and_qos_on_the_wire test_state_follows_joint_states_by_name
  test_plan_arrives_as_the_identical_trajectory test_lease_lapse_publishes_the_hold
  test_cancel_publishes_the_hold test_hold_of_a_silent_arm_is_the_setpoint
  test_estop_holds_and_refuses test_arm_that_falls_short_aborts
  test_silent_arm_is_a_fault test_missing_joint_is_a_fault test_no_controller_is_a_fault
  test_jog_is_a_short_trajectory_held_at_expiry test_gripper_is_refused test_ghost_for_rviz
  test_command_line_errors)
foreach(case IN LISTS ros2_driver_cases)
  add_test(NAME ros2_driver.${case}
           COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/ros2_driver_test.py
                   Ros2DriverTest.${case})
  set_tests_properties(ros2_driver.${case} PROPERTIES
    LABELS drivers TIMEOUT 120
    ENVIRONMENT "TELEAR_DATA_DIR=${TELEAR_DATA_DIR};TELEAR_BINARY=$<TARGET_FILE:telear>;TELEAR_ROS2_PEER=$<TARGET_FILE:ros2_test_peer>")
endforeach()
