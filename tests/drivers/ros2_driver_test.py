#!/usr/bin/python3
"""`telear robot-server --driver ros2` against a Cyclone DDS peer (issue 21, docs/ros2.md).

The peer (ros2_test_peer.cpp) is a ros2_control arm as DDS sees one: it publishes
sensor_msgs/msg/JointState on rt/joint_states (its own joint order, an extra joint) and takes
trajectory_msgs/msg/JointTrajectory on rt/joint_trajectory_controller/joint_trajectory, checking
each as the JointTrajectoryController does and following it; it also reports, from DDS discovery,
the type names and QoS of the endpoints telear creates. The robot server is driven over gRPC as
any client would. Each test has a DDS domain of its own, discovery on loopback only.

    ros2_driver_test.py [Ros2DriverTest.test_name ...]

Environment (set by CTest): TELEAR_BINARY, TELEAR_ROS2_PEER.
"""

import os
import shutil
import subprocess
import tempfile
import time
import unittest

import grpc

import ros2_harness as h
from ros1_harness import pb

TELEAR = os.environ.get("TELEAR_BINARY", "")
PEER = os.environ.get("TELEAR_ROS2_PEER", "")

# The PUMA away from its limits, and 0.3 rad further on the waist and the elbow.
Q0 = [0.1, -0.3, 0.4, 0.05, -0.6, 0.2]
Q1 = [0.4, -0.3, 0.1, 0.05, -0.6, 0.2]

TRAJECTORY_TOPIC = "rt/joint_trajectory_controller/joint_trajectory"


class Ros2DriverTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="telear-ros2-")
        self.domain_lease = h.Domain()
        self.domain = self.domain_lease.id
        self.processes = []

    def tearDown(self):
        for process in reversed(self.processes):
            process.stop()
        self.domain_lease.release()
        shutil.rmtree(self.dir, ignore_errors=True)

    def start_peer(self, peer_args=(), joints=h.PUMA_JOINTS):
        peer = h.Peer(PEER, self.domain, self.dir, joints=joints, initial=Q0, extra=peer_args)
        self.processes.append(peer)
        return peer

    def start_server(self, server_args=()):
        server = h.RobotServer(TELEAR, self.domain, self.dir, extra=server_args)
        self.processes.append(server)
        return server

    def start(self, peer_args=(), server_args=(), joints=h.PUMA_JOINTS):
        return self.start_peer(peer_args, joints), self.start_server(server_args)

    def wait_ready(self, server):
        """The driver has the arm's state and a subscriber on the trajectory topic (no fault)."""
        return server.wait_state(lambda s: not s.fault and len(s.q) == 6, 10,
                                 "the driver to see the arm and its controller")

    def run_plan(self, server, plan_id, waypoints, velocity_scale=0.5):
        plan = server.plan(plan_id, waypoints, velocity_scale)
        preview = server.preview(plan)
        return preview, server.execute(plan, preview)

    def assert_hold(self, trajectory, joints_q):
        """A hold: the controller's own stop, one point at time 0 where the arm is."""
        self.assertEqual(trajectory["joint_names"], h.PUMA_JOINTS)
        self.assertEqual(trajectory["times_ns"], [0])
        self.assertEqual(trajectory["stamp_ns"], 0)
        self.assertEqual(len(trajectory["positions"]), 1)
        # The driver's newest joint state is at most a publishing period or two old.
        for got, want in zip(trajectory["positions"][0], joints_q):
            self.assertAlmostEqual(got, want, delta=0.02)

    def assert_still(self, server, seconds=0.3):
        # From the arm's first joint state after the hold (the hold is where the arm was in the
        # driver's newest state, up to one publishing period behind it: a step back that small).
        time.sleep(0.1)
        before = list(server.state().q)
        time.sleep(seconds)
        self.assertEqual(list(server.state().q), before)

    # --- the wire ----------------------------------------------------------------------------

    def test_types_and_qos_on_the_wire(self):
        peer, server = self.start()
        self.wait_ready(server)

        def endpoint(kind, topic):
            found = [e for e in peer.events("endpoint") if e["kind"] == kind and
                     e["topic"] == topic]
            return found[0] if found else None

        trajectory = h.wait_for(lambda: endpoint("publication", TRAJECTORY_TOPIC), 5,
                                "telear's trajectory writer in DDS discovery")
        states = h.wait_for(lambda: endpoint("subscription", "rt/joint_states"), 5,
                            "telear's joint states reader in DDS discovery")
        ghost = h.wait_for(lambda: endpoint("publication", "rt/telear/ghost/joint_states"), 5,
                           "telear's ghost writer in DDS discovery")
        # ROS 2's type names as rmw_cyclonedds makes them, and only XCDR1 (plain CDR, id 0).
        self.assertEqual(trajectory["type"], "trajectory_msgs::msg::dds_::JointTrajectory_")
        self.assertEqual(states["type"], "sensor_msgs::msg::dds_::JointState_")
        self.assertEqual(ghost["type"], "sensor_msgs::msg::dds_::JointState_")
        for e in (trajectory, states, ghost):
            self.assertEqual(e["data_representation"], [0])
        # rclcpp's default publisher QoS; a best-effort reader matches any joint state publisher.
        self.assertEqual((trajectory["reliability"], trajectory["durability"],
                          trajectory["history_depth"]), ("reliable", "volatile", 10))
        self.assertEqual((states["reliability"], states["durability"]), ("best_effort",
                                                                          "volatile"))
        # ROS 2's latched.
        self.assertEqual((ghost["reliability"], ghost["durability"], ghost["history_depth"]),
                         ("reliable", "transient_local", 1))
        # Matched both ways: the peer's writer and reader use the same generated types.
        log = server.log_text()
        self.assertIn("rt/joint_states has 1 publisher(s)", log)
        self.assertIn(TRAJECTORY_TOPIC + " has 1 subscriber(s)", log)

    # --- state -------------------------------------------------------------------------------

    def test_state_follows_joint_states_by_name(self):
        _, server = self.start()
        info = server.info()
        self.assertEqual(info.driver, "ros2")
        self.assertEqual([j.name for j in info.joints], h.PUMA_JOINTS)
        state = self.wait_ready(server)
        # Published reversed with an extra joint in the middle: mapped back by name.
        self.assertEqual(list(state.q), Q0)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)
        # capture_ns is when the arm published (receipt less the message's age): recent.
        self.assertLess(h.monotonic_ns() - state.capture_ns, 500_000_000)

    # --- trajectories ------------------------------------------------------------------------

    def test_plan_arrives_as_the_identical_trajectory(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        preview, accepted = self.run_plan(server, "ros2-plan", [Q0, Q1, Q0])
        self.assertFalse(accepted.duplicate)
        self.assertEqual(accepted.plan_hash, preview.plan_hash)
        trajectory = h.wait_for(peer.trajectories, 5, "the trajectory at the peer")[0]
        self.assertEqual(trajectory["joint_names"], h.PUMA_JOINTS)
        self.assertEqual(trajectory["times_ns"], [s.time_from_start_ns for s in preview.samples])
        self.assertEqual(trajectory["positions"], [list(s.q) for s in preview.samples])
        self.assertEqual(trajectory["stamp_ns"], 0)  # start now
        self.assertEqual(trajectory["velocities"], 0)  # positions only
        print(f"accepted -> trajectory at the peer: "
              f"{(trajectory['received_ns'] - accepted.accepted_ns) * 1e-6:.2f} ms "
              f"({len(trajectory['times_ns'])} points)")
        self.assertGreaterEqual(trajectory["received_ns"], accepted.accepted_ns - 1_000_000)
        self.assertLess(trajectory["received_ns"] - accepted.accepted_ns, 1_000_000_000)
        self.assertEqual(peer.events("rejected"), [])
        running = server.state()
        self.assertEqual(running.trajectory_id, "ros2-plan")
        self.assertEqual(running.mode, pb.ROBOT_MODE_TRAJECTORY)
        done = server.wait_state(
            lambda s: s.last_trajectory_id == "ros2-plan" and
            s.last_trajectory_status == pb.TRAJECTORY_STATUS_COMPLETED,
            preview.duration_s + 5, "the plan to complete")
        # Completed only once its duration had passed and the arm was at its end.
        self.assertGreaterEqual(h.monotonic_ns() - accepted.accepted_ns,
                                int(preview.duration_s * 1e9))
        self.assertEqual(done.mode, pb.ROBOT_MODE_IDLE)
        # At its end to a micro-radian: a loaded machine's state read right after "completed"
        # has shown the peer's arm 0.3 micro-radians short.
        for got, want in zip(server.state().q, Q0):
            self.assertAlmostEqual(got, want, places=6)
        # The same id again: the first acceptance, no second trajectory.
        again = server.execute(server.plan("ros2-plan", [Q0, Q1, Q0]), preview)
        self.assertTrue(again.duplicate)
        time.sleep(0.2)
        self.assertEqual(len(peer.trajectories()), 1)

    def test_lease_lapse_publishes_the_hold(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire(heartbeat_ns=100_000_000)
        preview, _ = self.run_plan(server, "ros2-lapse", [Q0, Q1], velocity_scale=0.1)
        self.assertGreater(preview.duration_s, 1.0)
        h.wait_for(peer.trajectories, 5, "the trajectory")
        time.sleep(0.3)  # under way
        expires_ns = server.stop_heartbeat()
        hold = h.wait_for(lambda: peer.trajectories()[1:], 5, "the hold")[0]
        lapse_to_hold_ms = (hold["received_ns"] - expires_ns) * 1e-6
        print(f"lease lapse -> hold at the peer: {lapse_to_hold_ms:.1f} ms")
        self.assertGreaterEqual(lapse_to_hold_ms, 0.0)
        self.assertLessEqual(lapse_to_hold_ms, 300.0)
        self.assert_hold(hold, hold["q"])
        self.assertEqual(peer.events("rejected"), [])
        state = server.wait_state(
            lambda s: s.last_trajectory_id == "ros2-lapse" and
            s.last_trajectory_status == pb.TRAJECTORY_STATUS_CANCELLED, 5, "the record")
        self.assertIn("lease", state.last_trajectory_message)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)
        # Stopped short of the target, and stays there.
        self.assertGreater(state.q[0], Q0[0] + 1e-3)
        self.assertLess(state.q[0], Q1[0] - 1e-3)
        self.assert_still(server)

    def test_cancel_publishes_the_hold(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        self.run_plan(server, "ros2-cancel", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(peer.trajectories, 5, "the trajectory")
        time.sleep(0.3)
        server.call("Cancel", pb.CancelRequest(lease_id=server.lease.lease_id,
                                               reason="operator cancelled"))
        hold = h.wait_for(lambda: peer.trajectories()[1:], 2, "the hold")[0]
        self.assert_hold(hold, hold["q"])
        state = server.wait_state(
            lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_CANCELLED, 5, "the record")
        self.assertEqual(state.last_trajectory_id, "ros2-cancel")
        self.assertIn("operator cancelled", state.last_trajectory_message)
        self.assert_still(server)
        # At rest, a motion is accepted again from where the arm stopped.
        q = list(server.state().q)
        _, accepted = self.run_plan(server, "ros2-after-cancel", [q, Q0])
        self.assertFalse(accepted.duplicate)
        h.wait_for(lambda: peer.trajectories()[2:], 5, "the next trajectory")

    def test_hold_of_a_silent_arm_is_the_setpoint(self):
        # The arm goes on moving but its joint states stop: holding its last reported position
        # would send it back; the hold is where the trajectory has the controller now.
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        self.run_plan(server, "ros2-silent-hold", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(peer.trajectories, 5, "the trajectory")
        time.sleep(0.3)
        peer.set_silent(True)
        state = server.wait_state(lambda s: "silent" in s.fault, 3, "the silence fault")
        time.sleep(0.2)
        server.call("Cancel", pb.CancelRequest(lease_id=server.lease.lease_id, reason="stop"))
        hold = h.wait_for(lambda: peer.trajectories()[1:], 2, "the hold")[0]
        moved_while_silent = hold["q"][0] - state.q[0]
        print(f"waist moved {moved_while_silent:.3f} rad unheard; hold - arm: "
              f"{hold['positions'][0][0] - hold['q'][0]:.4f} rad")
        self.assertGreater(moved_while_silent, 0.02)
        self.assert_hold(hold, hold["q"])
        self.assertIn("holding the running trajectory's setpoint", server.log_text())

    def test_estop_holds_and_refuses(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        self.run_plan(server, "ros2-estop", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(peer.trajectories, 5, "the trajectory")
        server.call("EStop", pb.EStopRequest(reason="operator pressed E-STOP"))
        hold = h.wait_for(lambda: peer.trajectories()[1:], 2, "the hold")[0]
        self.assert_hold(hold, hold["q"])
        state = server.wait_state(
            lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_ABORTED, 5, "the record")
        self.assertTrue(state.estop)
        self.assertEqual(state.mode, pb.ROBOT_MODE_ESTOPPED)
        self.assertIn("operator pressed E-STOP", state.last_trajectory_message)
        q = list(state.q)
        with self.assertRaises(grpc.RpcError) as refused:
            self.run_plan(server, "ros2-after-estop", [q, Q0])
        self.assertEqual(refused.exception.code(), grpc.StatusCode.FAILED_PRECONDITION)
        self.assertIn("e-stop", refused.exception.details())
        self.assertEqual(len(peer.trajectories()), 2)
        server.call("ResetEStop", pb.ResetEStopRequest(lease_id=server.lease.lease_id))
        self.assertFalse(server.state().estop)
        # At rest the e-stop holds too (whatever else commands the controller is overridden).
        server.call("EStop", pb.EStopRequest(reason="second press"))
        at_rest = h.wait_for(lambda: peer.trajectories()[2:], 2, "the hold at rest")[0]
        self.assert_hold(at_rest, at_rest["q"])

    def test_arm_that_falls_short_aborts(self):
        # A blocked arm: it stops 0.3 s into every trajectory.
        _, server = self.start(peer_args=["--stall-after", "0.3"])
        self.wait_ready(server)
        server.acquire()
        preview, _ = self.run_plan(server, "ros2-short", [Q0, Q1], velocity_scale=0.5)
        state = server.wait_state(
            lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_ABORTED,
            preview.duration_s + 5, "the abort")
        self.assertEqual(state.last_trajectory_id, "ros2-short")
        self.assertIn("the arm did not reach the trajectory's last point within 1.00 s after its "
                      "duration: joint ", state.last_trajectory_message)
        self.assertIn("(tolerance 0.0100)", state.last_trajectory_message)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)

    # --- faults ------------------------------------------------------------------------------

    def test_silent_arm_is_a_fault(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        peer.set_silent(True)
        state = server.wait_state(lambda s: "silent" in s.fault, 3, "the silence fault")
        self.assertIn("the arm is silent: no /joint_states for", state.fault)
        self.assertIn("(limit 0.50 s)", state.fault)
        with self.assertRaises(grpc.RpcError) as refused:
            self.run_plan(server, "ros2-silent", [Q0, Q1])
        self.assertIn("the arm is silent", refused.exception.details())
        with self.assertRaises(grpc.RpcError) as jog_refused:
            server.call("Jog", pb.JogRequest(
                lease_id=server.lease.lease_id, expires_ns=h.monotonic_ns() + 10**9,
                joint_increment=pb.JointIncrement(joint=0, delta=0.01)))
        self.assertIn("the arm is silent", jog_refused.exception.details())
        self.assertEqual(peer.trajectories(), [])
        peer.set_silent(False)
        self.wait_ready(server)

    def test_missing_joint_is_a_fault(self):
        # An arm whose joint_states lack the wrist swivel.
        _, server = self.start(joints=h.PUMA_JOINTS[:5])
        state = server.wait_state(lambda s: "wrist_swivel" in s.fault, 5, "the missing joint")
        self.assertIn("/joint_states has no joint 'wrist_swivel' (the robot's joints: waist, "
                      "shoulder, elbow, wrist_roll, wrist_bend, wrist_swivel)", state.fault)

    def test_no_controller_is_a_fault(self):
        # The arm's controller is /arm_controller; telear looks for the default one.
        peer = self.start_peer(peer_args=["--controller", "/arm_controller"])
        server = self.start_server()
        state = server.wait_state(lambda s: "subscribes" in s.fault, 5, "the controller fault")
        self.assertEqual(state.fault, "nothing subscribes to "
                         "/joint_trajectory_controller/joint_trajectory "
                         "(trajectory_msgs/msg/JointTrajectory): is the "
                         "JointTrajectoryController active?")
        server.acquire()
        with self.assertRaises(grpc.RpcError) as refused:
            self.run_plan(server, "ros2-no-controller", [Q0, Q1])
        self.assertIn("nothing subscribes to", refused.exception.details())
        server.stop()
        # Named: ROS /arm_controller/joint_trajectory is DDS rt/arm_controller/joint_trajectory.
        named = self.start_server(["--ros2-controller", "/arm_controller"])
        self.wait_ready(named)
        named.acquire()
        self.run_plan(named, "ros2-named-controller", [Q0, Q1])
        h.wait_for(peer.trajectories, 5, "the trajectory on rt/arm_controller/joint_trajectory")

    # --- jogs and the gripper ----------------------------------------------------------------

    def test_jog_is_a_short_trajectory_held_at_expiry(self):
        peer, server = self.start()
        self.wait_ready(server)
        server.acquire()
        # 0.5 rad takes the waist well over a second; the jog expires after 0.3 s.
        expires_ns = h.monotonic_ns() + 300_000_000
        answer = server.call("Jog", pb.JogRequest(
            lease_id=server.lease.lease_id, expires_ns=expires_ns,
            joint_increment=pb.JointIncrement(joint=0, delta=0.5)))
        self.assertAlmostEqual(answer.target_q[0], Q0[0] + 0.5, places=12)
        jog = h.wait_for(peer.trajectories, 2, "the jog's trajectory")[0]
        self.assertEqual(jog["positions"][0], Q0)
        self.assertEqual(jog["positions"][-1], [Q0[0] + 0.5] + Q0[1:])
        self.assertEqual(jog["times_ns"][0], 0)
        hold = h.wait_for(lambda: peer.trajectories()[1:], 2, "the expiry's hold")[0]
        late_ms = (hold["received_ns"] - expires_ns) * 1e-6
        print(f"jog expiry -> hold at the peer: {late_ms:.1f} ms")
        self.assertGreaterEqual(late_ms, 0.0)
        self.assertLess(late_ms, 100.0)
        self.assert_hold(hold, hold["q"])
        rest = server.wait_state(lambda s: s.mode == pb.ROBOT_MODE_IDLE, 3, "the arm at rest")
        self.assertGreater(rest.q[0], Q0[0])
        self.assertLess(rest.q[0], Q0[0] + 0.5)

    def test_gripper_is_refused(self):
        peer, server = self.start()
        state = self.wait_ready(server)
        server.acquire()
        with self.assertRaises(grpc.RpcError) as refused:
            server.call("SetGripper", pb.SetGripperRequest(lease_id=server.lease.lease_id,
                                                           opening=0.5))
        self.assertIn("the ROS 2 driver has no gripper interface", refused.exception.details())
        # The opening the state reports, carried by every waypoint: no-ops, the plan runs.
        keep = server.plan("ros2-keep-gripper", [Q0, Q1])
        for waypoint in keep.waypoints:
            waypoint.has_gripper, waypoint.gripper_opening = True, state.gripper_opening
        server.execute(keep, server.preview(keep))
        server.wait_state(lambda s: s.last_trajectory_status == pb.TRAJECTORY_STATUS_COMPLETED,
                          10, "the plan to complete")
        # A plan that opens the gripper is refused: no arm motion without its grasp.
        grasp = server.plan("ros2-grasp", [Q1, Q0])
        grasp.waypoints[1].has_gripper, grasp.waypoints[1].gripper_opening = True, 1.0
        with self.assertRaises(grpc.RpcError) as refused:
            server.execute(grasp, server.preview(grasp))
        self.assertIn("it moves the gripper to 1.000", refused.exception.details())
        self.assertIn("the ROS 2 driver has no gripper interface", refused.exception.details())
        self.assertEqual(len(peer.trajectories()), 1)

    # --- what the operator rehearses, seen by ROS tools ------------------------------------

    def test_ghost_for_rviz(self):
        ghost_topic = ["--ghost-topic", "/telear/ghost/joint_states"]
        peer, server = self.start(peer_args=ghost_topic)
        self.wait_ready(server)
        preview = server.preview(server.plan("ros2-ghost", [Q0, Q1], velocity_scale=1.0))
        # Played in real time, then the last sample held.
        time.sleep(preview.duration_s + 0.3)
        frames = peer.events("ghost")
        self.assertGreater(len(frames), 3)
        self.assertEqual(frames[-1]["names"], h.PUMA_JOINTS)
        for got, want in zip(frames[-1]["position"], preview.samples[-1].q):
            self.assertAlmostEqual(got, want, places=9)
        # Transient local: a subscriber that comes later still gets the last frame.
        late = self.start_peer(peer_args=ghost_topic + ["--controller", "none"])
        frame = h.wait_for(lambda: late.events("ghost"), 5, "the held frame")[0]
        self.assertEqual(frame["position"], frames[-1]["position"])
        # Nothing moved: a preview is not a command.
        self.assertEqual(peer.trajectories(), [])
        self.assertEqual(list(server.state().q), Q0)
        # The lease holder's ghost rides on the heartbeat and is shown between previews.
        server.acquire(renew=False)
        pose = [0.2, -0.4, 0.5, 0.0, -0.5, 0.1]
        server.call("RenewLease", pb.RenewLeaseRequest(lease_id=server.lease.lease_id,
                                                       ghost_q=pose))
        rehearsed = h.wait_for(lambda: [e for e in late.events("ghost")
                                        if e["position"] == pose], 5, "the rehearsed ghost")
        self.assertEqual(rehearsed[0]["names"], h.PUMA_JOINTS)

    # --- the command line --------------------------------------------------------------------

    def test_command_line_errors(self):
        def run(*args, env=None):
            return subprocess.run([TELEAR, "robot-server", "--token-file", "/dev/null",
                                   "--listen", "127.0.0.1:0"] + list(args),
                                  capture_output=True, text=True, timeout=30,
                                  env=env or h.loopback_environment(self.dir))

        bad_driver = run("--driver", "ros3")
        self.assertEqual(bad_driver.returncode, 2)
        self.assertIn("--driver must be sim, ros1 or ros2, got 'ros3'", bad_driver.stderr)
        with_q = run("--driver", "ros2", "--q", "ready")
        self.assertEqual(with_q.returncode, 2)
        self.assertIn("--q sets the simulated robot's start; a ros2 arm is where it is",
                      with_q.stderr)
        bad_domain = run("--driver", "ros2", "--ros-domain", "233")
        self.assertEqual(bad_domain.returncode, 1)
        self.assertIn("ROS 2 driver: the ROS domain id must be 0..232, got 233", bad_domain.stderr)
        env = h.loopback_environment(self.dir)
        env["ROS_DOMAIN_ID"] = "seven"
        bad_env = run("--driver", "ros2", env=env)
        self.assertEqual(bad_env.returncode, 1)
        self.assertIn("ROS 2 driver: $ROS_DOMAIN_ID must be a domain id 0..232, got 'seven'",
                      bad_env.stderr)
        relative = run("--driver", "ros2", "--ros2-controller", "joint_trajectory_controller")
        self.assertEqual(relative.returncode, 1)
        self.assertIn("ROS 2 driver: the controller (--ros2-controller) must be an absolute ROS 2 "
                      "name such as /joint_trajectory_controller, got "
                      "'joint_trajectory_controller'", relative.stderr)
        bad_topic = run("--driver", "ros2", "--ros2-joint-states", "/arm/2states")
        self.assertEqual(bad_topic.returncode, 1)
        self.assertIn("ROS 2 driver: the joint states topic (--ros2-joint-states) must be an "
                      "absolute ROS 2 name", bad_topic.stderr)
        self.assertIn("got '/arm/2states'", bad_topic.stderr)
        env = h.loopback_environment(self.dir)
        env["CYCLONEDDS_URI"] = "<CycloneDDS><Domain><General><NoSuchSetting>1</NoSuchSetting>" \
                                "</General></Domain></CycloneDDS>"
        bad_config = run("--driver", "ros2", "--ros-domain", str(self.domain), env=env)
        self.assertEqual(bad_config.returncode, 1)
        self.assertIn(f"ROS 2 driver: cannot join DDS domain {self.domain} "
                      "(dds_create_participant: ", bad_config.stderr)
        self.assertIn("check $CYCLONEDDS_URI)", bad_config.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
