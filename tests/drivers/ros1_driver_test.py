#!/usr/bin/python3
"""`telear robot-server --driver ros1` against real ROS 1 peers (issue 21, docs/ros.md).

Debian's rosmaster (the CTest fixture's, or one of this test's own for the restart), the test
controller (a real actionlib control_msgs/FollowJointTrajectory server publishing
/joint_states in an order of its own with an extra joint, ros1_test_controller.cpp), and the
robot server as a process, driven over gRPC as any client would.

    ros1_driver_test.py [Ros1DriverTest.test_name ...]

Environment (set by CTest): TELEAR_BINARY, TELEAR_ROS1_CONTROLLER, TELEAR_ROS_TEST_DIR (the
fixture's master_uri is there), TELEAR_CONTROL_MSGS_INCLUDE (the generated headers).
"""

import math
import os
import re
import shutil
import subprocess
import tempfile
import time
import unittest

import grpc
import yaml

import ros1_harness as h
from ros1_harness import pb

TELEAR = os.environ.get("TELEAR_BINARY", "")
CONTROLLER = os.environ.get("TELEAR_ROS1_CONTROLLER", "")
ROS_DIR = os.environ.get("TELEAR_ROS_TEST_DIR", "")

# The PUMA away from its limits, and 0.3 rad further on the waist and the elbow.
Q0 = [0.1, -0.3, 0.4, 0.05, -0.6, 0.2]
Q1 = [0.4, -0.3, 0.1, 0.05, -0.6, 0.2]


def fixture_master_uri():
    with open(os.path.join(ROS_DIR, "master_uri")) as f:
        return f.read().strip()


class Ros1DriverTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="telear-ros1-")
        self.processes = []

    def tearDown(self):
        for process in reversed(self.processes):
            process.stop()
        shutil.rmtree(self.dir, ignore_errors=True)

    def start(self, controller_args=(), server_args=(), joints=h.PUMA_JOINTS, master_uri=None):
        master_uri = master_uri or fixture_master_uri()
        controller = h.Controller(CONTROLLER, master_uri, self.dir, joints=joints, initial=Q0,
                                  extra=controller_args)
        self.processes.append(controller)
        server = h.RobotServer(TELEAR, master_uri, self.dir, extra=server_args)
        self.processes.append(server)
        return controller, server

    def wait_ready(self, server):
        """The driver has the arm's state and the action server (no fault)."""
        return server.wait_state(lambda s: not s.fault and len(s.q) == 6, 10,
                                 "the driver to see the arm and its controller")

    def run_plan(self, server, plan_id, waypoints, velocity_scale=0.5):
        plan = server.plan(plan_id, waypoints, velocity_scale)
        preview = server.preview(plan)
        return preview, server.execute(plan, preview)

    # --- the generated interface -----------------------------------------------------------

    def test_control_msgs_md5(self):
        # Real controllers refuse a client whose goal MD5 differs from control_msgs'.
        include = os.environ["TELEAR_CONTROL_MSGS_INCLUDE"]
        with open(os.path.join(include, "control_msgs", "FollowJointTrajectoryGoal.h")) as f:
            header = f.read()
        md5 = re.search(r'MD5Sum<.*?return "([0-9a-f]{32})"', header, re.S).group(1)
        self.assertEqual(md5, "69636787b6ecbde4d61d711979bc7ecb")

    # --- state -------------------------------------------------------------------------------

    def test_state_follows_joint_states_by_name(self):
        _, server = self.start()
        info = server.info()
        self.assertEqual(info.driver, "ros1")
        self.assertEqual([j.name for j in info.joints], h.PUMA_JOINTS)
        state = self.wait_ready(server)
        # Published reversed with an extra joint in the middle: mapped back by name.
        self.assertEqual(list(state.q), Q0)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)
        # capture_ns is when the arm published (receipt less the message's age): recent.
        self.assertLess(h.monotonic_ns() - state.capture_ns, 500_000_000)

    # --- trajectories ------------------------------------------------------------------------

    def test_plan_arrives_as_the_identical_goal(self):
        controller, server = self.start()
        self.wait_ready(server)
        server.acquire()
        preview, accepted = self.run_plan(server, "ros1-plan", [Q0, Q1, Q0])
        self.assertFalse(accepted.duplicate)
        self.assertEqual(accepted.plan_hash, preview.plan_hash)
        goal = h.wait_for(lambda: controller.events("goal"), 5, "the goal at the controller")[0]
        self.assertEqual(goal["joint_names"], h.PUMA_JOINTS)
        self.assertEqual(goal["times_ns"], [s.time_from_start_ns for s in preview.samples])
        self.assertEqual(goal["positions"], [list(s.q) for s in preview.samples])
        # Received after the server accepted it, and soon.
        self.assertGreaterEqual(goal["received_ns"], accepted.accepted_ns - 1_000_000)
        self.assertLess(goal["received_ns"] - accepted.accepted_ns, 1_000_000_000)
        running = server.state()
        self.assertEqual(running.trajectory_id, "ros1-plan")
        self.assertEqual(running.mode, pb.ROBOT_MODE_TRAJECTORY)
        done = server.wait_state(
            lambda s: s.last_trajectory_id == "ros1-plan" and
            s.last_trajectory_status == pb.TRAJECTORY_STATUS_COMPLETED,
            preview.duration_s + 5, "the plan to complete")
        self.assertEqual(done.mode, pb.ROBOT_MODE_IDLE)
        for got, want in zip(server.state().q, Q0):
            self.assertAlmostEqual(got, want, places=9)
        # The same id again: the first acceptance, no second goal.
        again = server.execute(server.plan("ros1-plan", [Q0, Q1, Q0]), preview)
        self.assertTrue(again.duplicate)
        time.sleep(0.2)
        self.assertEqual(len(controller.events("goal")), 1)

    def test_feedback_gives_the_controllers_setpoint(self):
        # The arm 0.2 s behind its setpoint: the state shows both, so a monitor sees the lag.
        _, server = self.start(controller_args=["--lag", "0.2"])
        self.wait_ready(server)
        server.acquire()
        preview, _ = self.run_plan(server, "ros1-feedback", [Q0, Q1], velocity_scale=0.1)
        state = server.wait_state(
            lambda s: s.trajectory_id == "ros1-feedback" and 0.5 < s.trajectory_time_s < 1.0,
            5, "the middle of the plan")
        self.assertEqual(len(state.q_commanded), 6)
        # Moving the waist up: the setpoint is ahead of the arm, the elbow's down.
        self.assertGreater(state.q_commanded[0] - state.q[0], 0.002)
        self.assertLess(state.q_commanded[2] - state.q[2], -0.002)
        self.assertEqual(state.q_commanded[1], Q0[1])
        server.wait_state(lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_COMPLETED,
                          preview.duration_s + 5, "the plan to complete")

    def test_lease_lapse_cancels_the_goal(self):
        controller, server = self.start()
        self.wait_ready(server)
        server.acquire(heartbeat_ns=100_000_000)
        preview, _ = self.run_plan(server, "ros1-lapse", [Q0, Q1], velocity_scale=0.1)
        self.assertGreater(preview.duration_s, 1.0)
        h.wait_for(lambda: controller.events("goal"), 5, "the goal")
        expires_ns = server.stop_heartbeat()
        cancel = h.wait_for(lambda: controller.events("cancel"), 5, "the cancel")[0]
        lapse_to_cancel_ms = (cancel["received_ns"] - expires_ns) * 1e-6
        print(f"lease lapse -> cancel at the controller: {lapse_to_cancel_ms:.1f} ms")
        self.assertGreaterEqual(lapse_to_cancel_ms, 0.0)
        self.assertLessEqual(lapse_to_cancel_ms, 300.0)
        state = server.wait_state(
            lambda s: s.last_trajectory_id == "ros1-lapse" and
            s.last_trajectory_status == pb.TRAJECTORY_STATUS_CANCELLED, 5, "the record")
        self.assertIn("lease", state.last_trajectory_message)
        # Stopped short of the target.
        self.assertLess(abs(state.q[0] - Q0[0]), abs(Q1[0] - Q0[0]) - 1e-3)

    def test_estop_cancels_and_refuses(self):
        controller, server = self.start()
        self.wait_ready(server)
        server.acquire()
        self.run_plan(server, "ros1-estop", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(lambda: controller.events("goal"), 5, "the goal")
        server.call("EStop", pb.EStopRequest(reason="operator pressed E-STOP"))
        h.wait_for(lambda: controller.events("cancel"), 2, "the cancel")
        state = server.wait_state(
            lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_ABORTED, 5, "the record")
        self.assertTrue(state.estop)
        self.assertEqual(state.mode, pb.ROBOT_MODE_ESTOPPED)
        self.assertIn("operator pressed E-STOP", state.last_trajectory_message)
        q = list(state.q)
        with self.assertRaises(grpc.RpcError) as refused:
            self.run_plan(server, "ros1-after-estop", [q, Q0])
        self.assertEqual(refused.exception.code(), grpc.StatusCode.FAILED_PRECONDITION)
        self.assertIn("e-stop", refused.exception.details())
        self.assertEqual(len(controller.events("goal")), 1)
        server.call("ResetEStop", pb.ResetEStopRequest(lease_id=server.lease.lease_id))
        self.assertFalse(server.state().estop)

    def test_controller_abort_reports_its_error_string(self):
        _, server = self.start(controller_args=["--abort-after", "0.2", "--abort-message",
                                                "wrist_bend left its path tolerance by 0.2 rad"])
        self.wait_ready(server)
        server.acquire()
        self.run_plan(server, "ros1-abort", [Q0, Q1], velocity_scale=0.1)
        state = server.wait_state(
            lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_ABORTED, 5, "the abort")
        self.assertEqual(state.last_trajectory_id, "ros1-abort")
        self.assertIn("wrist_bend left its path tolerance by 0.2 rad",
                      state.last_trajectory_message)
        self.assertIn("error_code -4", state.last_trajectory_message)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)

    def test_gripper_events_without_a_gripper_action(self):
        controller, server = self.start()
        state = self.wait_ready(server)
        server.acquire()
        # The opening the state reports, carried by every waypoint: no-ops, the plan runs.
        keep = server.plan("ros1-keep-gripper", [Q0, Q1])
        for waypoint in keep.waypoints:
            waypoint.has_gripper, waypoint.gripper_opening = True, state.gripper_opening
        server.execute(keep, server.preview(keep))
        h.wait_for(lambda: controller.events("goal"), 5, "the goal")
        server.wait_state(lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_COMPLETED,
                          10, "the plan to complete")
        # A plan that closes or opens the gripper is refused: no arm motion without its grasp.
        grasp = server.plan("ros1-grasp", [Q1, Q0])
        grasp.waypoints[1].has_gripper, grasp.waypoints[1].gripper_opening = True, 1.0
        with self.assertRaises(grpc.RpcError) as refused:
            server.execute(grasp, server.preview(grasp))
        self.assertIn("it moves the gripper to 1.000", refused.exception.details())
        self.assertIn("no gripper action (telear robot-server --gripper-action NS)",
                      refused.exception.details())
        self.assertEqual(len(controller.events("goal")), 1)

    # --- faults ------------------------------------------------------------------------------

    def test_silent_arm_is_a_fault(self):
        controller, server = self.start()
        self.wait_ready(server)
        server.acquire()
        controller.set_silent(True)
        state = server.wait_state(lambda s: "silent" in s.fault, 3, "the silence fault")
        self.assertIn("no /joint_states for", state.fault)
        with self.assertRaises(grpc.RpcError) as refused:
            self.run_plan(server, "ros1-silent", [Q0, Q1])
        self.assertIn("the arm is silent", refused.exception.details())
        with self.assertRaises(grpc.RpcError) as jog_refused:
            server.call("Jog", pb.JogRequest(
                lease_id=server.lease.lease_id, expires_ns=state.capture_ns + 10**10,
                joint_increment=pb.JointIncrement(joint=0, delta=0.01)))
        self.assertIn("the arm is silent", jog_refused.exception.details())
        self.assertEqual(controller.events("goal"), [])
        controller.set_silent(False)
        self.wait_ready(server)

    def test_missing_joint_is_a_fault(self):
        # A controller whose joint_states lack the wrist swivel.
        _, server = self.start(joints=h.PUMA_JOINTS[:5])
        state = server.wait_state(lambda s: "wrist_swivel" in s.fault, 5, "the missing joint")
        self.assertIn("/joint_states has no joint 'wrist_swivel'", state.fault)

    # --- jogs and the gripper ----------------------------------------------------------------

    def test_jog_is_a_short_goal_cancelled_at_expiry(self):
        controller, server = self.start()
        state = self.wait_ready(server)
        server.acquire()
        # 0.5 rad takes the waist well over a second; the jog expires after 0.3 s.
        expires_ns = h.monotonic_ns() + 300_000_000
        answer = server.call("Jog", pb.JogRequest(
            lease_id=server.lease.lease_id, expires_ns=expires_ns,
            joint_increment=pb.JointIncrement(joint=0, delta=0.5)))
        self.assertAlmostEqual(answer.target_q[0], Q0[0] + 0.5, places=12)
        goal = h.wait_for(lambda: controller.events("goal"), 2, "the jog's goal")[0]
        self.assertEqual(goal["positions"][0], Q0)
        self.assertEqual(goal["positions"][-1], [Q0[0] + 0.5] + Q0[1:])
        cancel = h.wait_for(lambda: controller.events("cancel"), 2, "the expiry's cancel")[0]
        late_ms = (cancel["received_ns"] - expires_ns) * 1e-6
        self.assertGreaterEqual(late_ms, 0.0)
        self.assertLess(late_ms, 100.0)
        rest = server.wait_state(lambda s: s.mode == pb.ROBOT_MODE_IDLE, 3, "the arm at rest")
        self.assertGreater(rest.q[0], Q0[0])
        self.assertLess(rest.q[0], Q0[0] + 0.5)

    def test_gripper_command(self):
        controller, server = self.start(
            controller_args=["--gripper-ns", "/gripper_controller/gripper_cmd"],
            server_args=["--gripper-action", "/gripper_controller/gripper_cmd"])
        self.wait_ready(server)
        server.acquire()
        h.wait_for(lambda: "connected to the gripper action server" in server.log_text(), 5,
                   "the gripper action server")
        server.call("SetGripper", pb.SetGripperRequest(lease_id=server.lease.lease_id,
                                                       opening=0.5))
        event = h.wait_for(lambda: controller.events("gripper"), 3, "the gripper goal")[0]
        # Half the maximum opening, in metres: the PUMA's DH table names no gripper joints, so
        # the robot description's default of 80 mm (core::Gripper::max_opening_m).
        self.assertAlmostEqual(event["position"], 0.04, places=12)

    # --- what the operator rehearses, seen by ROS tools ------------------------------------

    def rostopic_echo(self, topic, master_uri):
        env = h.ros_master.loopback_environment(self.dir)
        env["ROS_MASTER_URI"] = master_uri
        # Debian's rostopic (python3-rostopic), with Debian's interpreter.
        return subprocess.run(["/usr/bin/python3", "/usr/bin/rostopic", "echo", "-n", "1",
                               topic], capture_output=True, text=True, timeout=30, env=env)

    def test_ghost_and_workspace_for_rviz(self):
        workspace = os.path.join(h.SOURCE_DIR, "data", "workspaces", "puma560_table.yaml")
        _, server = self.start(server_args=["--workspace", workspace])
        self.wait_ready(server)
        self.assertTrue(server.info().collision_checked)
        preview = server.preview(server.plan("ros1-ghost", [Q0, Q1], velocity_scale=1.0))
        # Played in real time, then the last sample held (latched): a late subscriber sees it.
        time.sleep(preview.duration_s + 0.3)
        ghost = self.rostopic_echo("/telear/ghost/joint_states", fixture_master_uri())
        message = yaml.safe_load(ghost.stdout.split("\n---")[0])
        self.assertEqual(message["name"], h.PUMA_JOINTS)
        for got, want in zip(message["position"], preview.samples[-1].q):
            self.assertAlmostEqual(got, want, places=6)
        markers = self.rostopic_echo("/telear/workspace", fixture_master_uri())
        self.assertEqual(markers.returncode, 0, markers.stderr)
        array = yaml.safe_load(markers.stdout.split("\n---")[0])
        table = [m for m in array["markers"] if m["ns"] == "table_top"]
        self.assertEqual(len(table), 1)
        self.assertEqual(table[0]["header"]["frame_id"], "base_link")
        self.assertEqual(table[0]["type"], 1)  # CUBE
        self.assertAlmostEqual(table[0]["scale"]["z"], 0.03, places=9)
        # Nothing moved: a preview is not a command.
        self.assertEqual(list(server.state().q), Q0)
        # Debian's robot_state_publisher beside the ghost topic, as docs/ros.md says to run it
        # for RViz: the robot's URDF is there, and the ghost's links come out as ghost/ frames.
        env = h.ros_master.loopback_environment(self.dir)
        env["ROS_MASTER_URI"] = fixture_master_uri()
        publisher = subprocess.Popen(
            ["/usr/lib/robot_state_publisher/robot_state_publisher", "__ns:=/telear/ghost",
             "_tf_prefix:=ghost", "joint_states:=/telear/ghost/joint_states"], env=env,
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        try:
            tf = subprocess.Popen(["/usr/bin/python3", "/usr/bin/rostopic", "echo", "-n", "1",
                                   "/tf"], env=env, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True)
            time.sleep(1.0)  # both subscribed before the next preview plays
            server.preview(server.plan("ros1-ghost-2", [Q0, Q1], velocity_scale=1.0))
            out, err = tf.communicate(timeout=20)
            self.assertEqual(tf.returncode, 0, err)
            frames = yaml.safe_load(out.split("\n---")[0])["transforms"]
            children = {t["child_frame_id"] for t in frames}
            self.assertIn("ghost/link1", children)
            self.assertTrue(all(c.startswith("ghost/") for c in children), children)
        finally:
            publisher.terminate()
            publisher.wait(10)

    def test_the_operators_ghost_for_rviz(self):
        _, server = self.start()
        self.wait_ready(server)
        lease = server.acquire(renew=False)
        ghost = [0.2, -0.1, 0.3, 0.0, -0.5, 0.1]
        # The console's heartbeat carries its ghost (RobotClient::set_ghost); here by hand.
        server.call("RenewLease", pb.RenewLeaseRequest(lease_id=lease.lease_id, ghost_q=ghost,
                                                       ghost_gripper=0.5))
        echoed = self.rostopic_echo("/telear/ghost/joint_states", fixture_master_uri())
        self.assertEqual(echoed.returncode, 0, echoed.stderr)
        message = yaml.safe_load(echoed.stdout.split("\n---")[0])
        self.assertEqual(message["name"], h.PUMA_JOINTS)
        self.assertEqual(message["position"], ghost)
        self.assertEqual(list(server.state().q), Q0)  # the ghost moves nothing

    # --- the master --------------------------------------------------------------------------

    def test_master_restart_reconnects(self):
        process, uri = h.ros_master.start_master(self.dir)
        port = int(uri.rsplit(":", 1)[1])
        try:
            controller, server = self.start(master_uri=uri)
            self.wait_ready(server)
            server.acquire()
            h.ros_master.stop_pid(process.pid)
            process.wait()
            state = server.wait_state(lambda s: "master" in s.fault, 5, "the master fault")
            self.assertIn("the ROS master does not answer", state.fault)
            with self.assertRaises(grpc.RpcError) as refused:
                self.run_plan(server, "ros1-no-master", [Q0, Q1])
            self.assertIn("the ROS master does not answer", refused.exception.details())
            # The master comes back on its port; the arm's controller is restarted with it
            # (a ROS 1 node does not re-register by itself), telear's server is not.
            process, _ = h.ros_master.start_master(self.dir, port=port)
            controller.stop()
            self.processes.remove(controller)
            controller = h.Controller(CONTROLLER, uri, self.dir, initial=Q0)
            self.processes.insert(0, controller)
            self.wait_ready(server)
            self.assertIn("lost the ROS master", server.log_text())
            self.assertGreaterEqual(server.log_text().count("connected to the ROS master"), 2)
            _, accepted = self.run_plan(server, "ros1-after-restart", [Q0, Q1])
            self.assertFalse(accepted.duplicate)
            h.wait_for(lambda: controller.events("goal"), 5, "the goal after the restart")
        finally:
            for p in self.processes:
                p.stop()
            self.processes = []
            h.ros_master.stop_pid(process.pid)

    # --- the command line --------------------------------------------------------------------

    def test_command_line_errors(self):
        def run(*args, env=None):
            return subprocess.run([TELEAR, "robot-server", "--token-file", "/dev/null"] +
                                  list(args), capture_output=True, text=True, timeout=30,
                                  env=env)

        bad_driver = run("--driver", "ros3")
        self.assertEqual(bad_driver.returncode, 2)
        self.assertIn("--driver must be sim, ros1 or ros2, got 'ros3'", bad_driver.stderr)
        with_q = run("--driver", "ros1", "--q", "ready")
        self.assertEqual(with_q.returncode, 2)
        self.assertIn("--q sets the simulated robot's start", with_q.stderr)
        env = dict(os.environ)
        env.pop("ROS_MASTER_URI", None)
        no_master = run("--driver", "ros1", "--listen", "127.0.0.1:0", env=env)
        self.assertEqual(no_master.returncode, 1)
        self.assertIn("no ROS master: give --ros-master http://HOST:PORT or set ROS_MASTER_URI",
                      no_master.stderr)
        bad_uri = run("--driver", "ros1", "--ros-master", "127.0.0.1:11311")
        self.assertEqual(bad_uri.returncode, 1)
        self.assertIn("must look like http://HOST:PORT, got '127.0.0.1:11311'", bad_uri.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
