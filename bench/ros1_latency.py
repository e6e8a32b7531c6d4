#!/usr/bin/python3
"""The ROS 1 driver's latencies (issue 21, docs/ros.md, "Measured"), with real ROS peers on this
machine: Debian's rosmaster, the tests' FollowJointTrajectory controller
(tests/drivers/ros1_test_controller.cpp) and `telear robot-server --driver ros1`, over gRPC.

    bench/ros1_latency.py --telear build/telear \\
        --controller build/tests/drivers/ros1_test_controller [--plans 100] [--lapses 20] [--json F]

  plan_to_goal_ms     ExecutePlan accepted (the server's accepted_ns) -> the goal received by the
                      controller's action server (its callback), over --plans plans
  lapse_to_cancel_ms  a lease's expiry (expires_ns of its last renewal) -> the cancel received by
                      the controller, over --lapses lapses during a running plan
  state_to_client_ms  a joint_states message's capture (its stamp, on the server clock) -> the
                      StreamState message carrying it received by a gRPC client (250 Hz stream)

Every time is CLOCK_MONOTONIC of this one machine (the server's clock), so the differences
need no clock synchronisation. Goals: <= 5 ms, <= 300 ms, <= 5 ms (p50/p99, p99, p50).
"""

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "drivers"))

import ros1_harness as h  # noqa: E402
from ros1_harness import pb  # noqa: E402

Q0 = [0.1, -0.3, 0.4, 0.05, -0.6, 0.2]


def percentile(values, p):
    ordered = sorted(values)
    k = min(len(ordered) - 1, max(0, int(round(p / 100.0 * (len(ordered) - 1)))))
    return ordered[k]


def summary(values):
    return {"n": len(values), "p50": percentile(values, 50), "p99": percentile(values, 99),
            "max": max(values), "mean": statistics.fmean(values)}


def plan_to_goal(server, controller, plans):
    delays = []
    q = list(Q0)
    for k in range(plans):
        target = list(q)
        target[0] = Q0[0] + (0.02 if k % 2 == 0 else 0.0)
        plan = server.plan(f"bench-plan-{k}", [q, target], velocity_scale=1.0)
        preview = server.preview(plan)
        accepted = server.execute(plan, preview)
        goal = h.wait_for(lambda: [g for g in controller.events("goal")][k:], 5, "the goal")[0]
        delays.append((goal["received_ns"] - accepted.accepted_ns) * 1e-6)
        server.wait_state(lambda s: s.last_trajectory_id == f"bench-plan-{k}" and
                          s.mode == pb.ROBOT_MODE_IDLE, 5, "the plan to complete")
        q = target
    return delays


def lapse_to_cancel(server, controller, lapses):
    delays = []
    for k in range(lapses):
        state = server.wait_state(lambda s: s.mode == pb.ROBOT_MODE_IDLE, 5, "rest")
        q = list(state.q)
        server.acquire(heartbeat_ns=100_000_000)
        target = list(q)
        target[0] = q[0] + (0.3 if q[0] < 0.5 else -0.3)
        plan = server.plan(f"bench-lapse-{k}", [q, target], velocity_scale=0.1)
        server.execute(plan, server.preview(plan))
        cancels_before = len(controller.events("cancel"))
        time.sleep(0.2)
        expires_ns = server.stop_heartbeat()
        cancel = h.wait_for(lambda: controller.events("cancel")[cancels_before:], 5,
                            "the cancel")[0]
        delays.append((cancel["received_ns"] - expires_ns) * 1e-6)
    return delays


def state_to_client(server, messages):
    stream = server.stub.StreamState(pb.StreamStateRequest(rate_hz=250), metadata=server.metadata)
    delays = []
    last_capture = None
    try:
        for state in stream:
            received = h.monotonic_ns()
            # Each joint_states message once: the stream repeats the latest state between them.
            if state.capture_ns != last_capture:
                last_capture = state.capture_ns
                delays.append((received - state.capture_ns) * 1e-6)
            if len(delays) >= messages:
                break
    finally:
        stream.cancel()
    return delays


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--telear", required=True)
    parser.add_argument("--controller", required=True)
    parser.add_argument("--plans", type=int, default=100)
    parser.add_argument("--lapses", type=int, default=20)
    parser.add_argument("--states", type=int, default=1000)
    parser.add_argument("--json")
    args = parser.parse_args()

    directory = tempfile.mkdtemp(prefix="telear-ros1-bench-")
    master, uri = h.ros_master.start_master(directory)
    processes = []
    try:
        controller = h.Controller(os.path.abspath(args.controller), uri, directory, initial=Q0)
        processes.append(controller)
        server = h.RobotServer(os.path.abspath(args.telear), uri, directory,
                               extra=["--log-level", "warn"])
        processes.append(server)
        server.wait_state(lambda s: not s.fault, 10, "the arm")
        server.acquire()
        results = {"plan_to_goal_ms": summary(plan_to_goal(server, controller, args.plans))}
        server.stop_heartbeat()
        server.call("ReleaseLease", pb.ReleaseLeaseRequest(lease_id=server.lease.lease_id))
        results["lapse_to_cancel_ms"] = summary(lapse_to_cancel(server, controller, args.lapses))
        results["state_to_client_ms"] = summary(state_to_client(server, args.states))
    finally:
        for process in reversed(processes):
            process.stop()
        h.ros_master.stop_pid(master.pid)
        shutil.rmtree(directory, ignore_errors=True)

    for name, s in results.items():
        print(f"{name:20s} n={s['n']:5d}  p50 {s['p50']:8.3f}  p99 {s['p99']:8.3f}  "
              f"max {s['max']:8.3f}  mean {s['mean']:8.3f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=2)


if __name__ == "__main__":
    main()
