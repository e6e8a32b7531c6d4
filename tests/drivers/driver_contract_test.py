#!/usr/bin/python3
"""The RobotDriver contract, the same cases against every driver (docs/ros.md, DESIGN's "a driver
is a plug"): `telear robot-server --driver sim` and `--driver ros1` (with the tests' ROS 1
controller on the CTest fixture's master), driven over gRPC by the same client code.

    driver_contract_test.py [SimDriverContract | Ros1DriverContract][.test_name]

The contract: the state in the URDF's joint order; a trajectory executed as one unit with its
record; an id executed once; Cancel and the e-stop stop at once, with the reason recorded;
the e-stop latches and refuses motion until reset; a jog reaches its target.
"""

import os
import shutil
import tempfile
import unittest

import grpc

import ros1_harness as h
from ros1_harness import pb

TELEAR = os.environ.get("TELEAR_BINARY", "")
CONTROLLER = os.environ.get("TELEAR_ROS1_CONTROLLER", "")
ROS_DIR = os.environ.get("TELEAR_ROS_TEST_DIR", "")

Q0 = [0.1, -0.3, 0.4, 0.05, -0.6, 0.2]
Q1 = [0.4, -0.3, 0.1, 0.05, -0.6, 0.2]
Q0_TEXT = ",".join(repr(v) for v in Q0)


class DriverContract:
    """The cases; a subclass starts the server with its driver, at Q0."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="telear-contract-")
        self.processes = []
        self.server = self.start_server()
        self.server.wait_state(lambda s: not s.fault and len(s.q) == 6, 10, "the arm")
        self.server.acquire()

    def tearDown(self):
        for process in reversed(self.processes):
            process.stop()
        shutil.rmtree(self.dir, ignore_errors=True)

    def execute(self, plan_id, waypoints, velocity_scale=0.5):
        plan = self.server.plan(plan_id, waypoints, velocity_scale)
        preview = self.server.preview(plan)
        return preview, self.server.execute(plan, preview)

    def record(self, plan_id, status, timeout_s):
        return self.server.wait_state(
            lambda s: s.last_trajectory_id == plan_id and s.last_trajectory_status == status,
            timeout_s, f"{plan_id} {pb.TrajectoryStatus.Name(status)}")

    def test_state_in_urdf_order(self):
        info = self.server.info()
        self.assertEqual([j.name for j in info.joints], h.PUMA_JOINTS)
        state = self.server.state()
        for got, want in zip(state.q, Q0):
            self.assertAlmostEqual(got, want, places=9)
        self.assertEqual(state.mode, pb.ROBOT_MODE_IDLE)

    def test_a_plan_runs_once_as_one_unit(self):
        preview, accepted = self.execute("contract-plan", [Q0, Q1])
        self.assertFalse(accepted.duplicate)
        running = self.server.state()
        self.assertEqual(running.trajectory_id, "contract-plan")
        done = self.record("contract-plan", pb.TRAJECTORY_STATUS_COMPLETED,
                           preview.duration_s + 5)
        self.assertEqual(done.mode, pb.ROBOT_MODE_IDLE)
        for got, want in zip(self.server.state().q, Q1):
            self.assertAlmostEqual(got, want, places=6)
        # ExecutePlan again with the same id (a retry after a lost reply): the first acceptance.
        again = self.server.execute(self.server.plan("contract-plan", [Q0, Q1]), preview)
        self.assertTrue(again.duplicate)
        self.assertEqual(again.accepted_ns, accepted.accepted_ns)

    def test_cancel_stops_with_the_reason(self):
        self.execute("contract-cancel", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(lambda: self.server.state().q[0] > Q0[0] + 0.005, 5, "motion")
        self.server.call("Cancel", pb.CancelRequest(lease_id=self.server.lease.lease_id,
                                                    reason="operator cancelled the move"))
        state = self.record("contract-cancel", pb.TRAJECTORY_STATUS_CANCELLED, 5)
        self.assertIn("operator cancelled the move", state.last_trajectory_message)
        rest = self.server.wait_state(lambda s: s.mode == pb.ROBOT_MODE_IDLE, 5, "rest")
        self.assertLess(rest.q[0], Q1[0] - 0.01)

    def test_estop_latches_and_refuses(self):
        self.execute("contract-estop", [Q0, Q1], velocity_scale=0.1)
        h.wait_for(lambda: self.server.state().q[0] > Q0[0] + 0.005, 5, "motion")
        self.server.call("EStop", pb.EStopRequest(reason="hand in the cell"))
        state = self.record("contract-estop", pb.TRAJECTORY_STATUS_ABORTED, 5)
        self.assertTrue(state.estop)
        self.assertEqual(state.estop_reason, "hand in the cell")
        self.assertEqual(state.mode, pb.ROBOT_MODE_ESTOPPED)
        q = list(self.server.wait_state(lambda s: max(abs(v) for v in s.qd) == 0.0, 5,
                                        "the arm at rest").q)
        with self.assertRaises(grpc.RpcError) as refused:
            self.execute("contract-after-estop", [q, Q0])
        self.assertEqual(refused.exception.code(), grpc.StatusCode.FAILED_PRECONDITION)
        self.assertIn("e-stop", refused.exception.details())
        self.server.call("ResetEStop", pb.ResetEStopRequest(lease_id=self.server.lease.lease_id))
        self.assertFalse(self.server.state().estop)
        self.execute("contract-after-reset", [q, Q0])
        self.record("contract-after-reset", pb.TRAJECTORY_STATUS_COMPLETED, 20)

    def test_a_jog_reaches_its_target(self):
        answer = self.server.call("Jog", pb.JogRequest(
            lease_id=self.server.lease.lease_id, expires_ns=h.monotonic_ns() + 3_000_000_000,
            joint_increment=pb.JointIncrement(joint=1, delta=0.05)))
        self.assertAlmostEqual(answer.target_q[1], Q0[1] + 0.05, places=12)
        state = self.server.wait_state(
            lambda s: s.mode == pb.ROBOT_MODE_IDLE and abs(s.q[1] - (Q0[1] + 0.05)) < 1e-6, 5,
            "the jog's target")
        self.assertAlmostEqual(state.q[0], Q0[0], places=9)


class SimDriverContract(DriverContract, unittest.TestCase):
    def start_server(self):
        server = h.RobotServer(TELEAR, "", self.dir, driver_args=["--driver", "sim", "--q", Q0_TEXT])
        self.processes.append(server)
        return server


class Ros1DriverContract(DriverContract, unittest.TestCase):
    def start_server(self):
        with open(os.path.join(ROS_DIR, "master_uri")) as f:
            uri = f.read().strip()
        self.processes.append(h.Controller(CONTROLLER, uri, self.dir, initial=Q0))
        server = h.RobotServer(TELEAR, uri, self.dir)
        self.processes.append(server)
        return server


if __name__ == "__main__":
    unittest.main(verbosity=2)
