#!/usr/bin/python3
"""A telear robot client in Python: read the state, take the lease, run a short trajectory.

Then it sends a plan, the waypoints themselves instead of samples ("the plan is the
message"): PreviewPlan asks the server to time and check four waypoints (one a via point,
passed without stopping) and answers the SHA-256 of the timed trajectory, which Python could
not compute without telear's own time parameterization; ExecutePlan with that hash runs
exactly what was previewed, and the same plan with a tampered hash is refused.

Then, when the server checks collisions against a workspace (GetInfo's collision_checked and
workspace_yaml; `telear robot-server --workspace data/workspaces/puma560_table.yaml`), it
sends the PUMA 560 a trajectory that ends with the hand inside the table and prints the
server's refusal: the server is the collision authority and the arm does not move.

Run with Debian's python3-grpcio and python3-grpc-tools (/usr/bin/python3, see
docs/network.md):

    /usr/bin/python3 examples/python/robot_example.py --address 127.0.0.1:50051 \\
        --token-file token.txt

The Python stubs are generated at run time from proto/ into a temporary directory with
grpc_tools.protoc, so the example always matches the wire format of its checkout.

The trajectory moves the waist 0.1 rad and back. It is sampled from a cosine time scaling
s(t) = (1 - cos(pi t / T)) / 2, which starts and ends at rest; its peak speed d pi / (2 T)
and acceleration d pi^2 / (2 T^2) are kept under half the joint's limits (GetInfo), so the
server's validation (velocity and acceleration as finite differences) passes.
"""

import argparse
import math
import os
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PROTO_DIR = os.path.normpath(os.path.join(HERE, "..", "..", "proto"))


def load_stubs(out_dir):
    """Generates telear/v1/*_pb2*.py into out_dir and imports them."""
    from grpc_tools import protoc  # python3-grpc-tools

    args = ["protoc", "-I", PROTO_DIR, "--python_out", out_dir, "--grpc_python_out", out_dir,
            "telear/v1/common.proto", "telear/v1/robot.proto"]
    if protoc.main(args) != 0:
        sys.exit("robot_example: protoc failed on " + PROTO_DIR)
    sys.path.insert(0, out_dir)
    from telear.v1 import robot_pb2, robot_pb2_grpc  # noqa: E402
    return robot_pb2, robot_pb2_grpc


# The PUMA 560 with its wrist centre 10 cm below the table top's upper face (x 0.45 m,
# y -0.60 m, z 0.30 m in the base frame), hand pointing down: from the robot's IK.
Q_INTO_TABLE = [-0.7259, -0.7761, -0.9089, 0.0, -1.4566, 0.0]


def cosine_move(q0, q1, joints, rate_hz):
    """(t, q) samples from q0 to q1 on a cosine time scaling, within half the limits."""
    duration_s = 0.5
    for a, b, j in zip(q0, q1, joints):
        d = abs(b - a)
        duration_s = max(duration_s, d * math.pi / (2 * 0.5 * j.max_velocity),
                         math.sqrt(d * math.pi ** 2 / (2 * 0.5 * j.max_acceleration)))
    n = int(math.ceil(duration_s * rate_hz))
    samples = []
    for k in range(n + 1):
        t = k / n * duration_s
        s = 0.5 * (1.0 - math.cos(math.pi * t / duration_s))
        samples.append((t, [a + (b - a) * s for a, b in zip(q0, q1)]))
    return samples


def cosine_samples(q0, joint, delta, duration_s, rate_hz):
    """(t, q) samples from q0 to q0 + delta on one joint and back, at rest at both ends."""
    n = int(math.ceil(duration_s * rate_hz))
    samples = []
    for leg, (a, b) in enumerate(((0.0, delta), (delta, 0.0))):
        for k in range(0 if leg == 0 else 1, n + 1):
            t = k / n * duration_s
            s = 0.5 * (1.0 - math.cos(math.pi * t / duration_s))
            q = list(q0)
            q[joint] += a + (b - a) * s
            samples.append((leg * duration_s + t, q))
    return samples


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--address", default="127.0.0.1:50051")
    parser.add_argument("--token-file", required=True)
    parser.add_argument("--name", default="python-example")
    args = parser.parse_args()

    import grpc  # python3-grpcio

    with open(args.token_file) as f:
        token = f.readline().strip()
    metadata = [("authorization", "Bearer " + token), ("telear-client", args.name)]

    with tempfile.TemporaryDirectory() as stubs_dir:
        pb, pb_grpc = load_stubs(stubs_dir)
        channel = grpc.insecure_channel(args.address)
        stub = pb_grpc.RobotServiceStub(channel)

        # 1. The robot and its current state (one message of the state stream).
        info = stub.GetInfo(pb.GetInfoRequest(), metadata=metadata, timeout=5)
        stream = stub.StreamState(pb.StreamStateRequest(rate_hz=50), metadata=metadata)
        state = next(stream)
        stream.cancel()
        q0 = list(state.q)
        print(f"robot {info.model_name} ({info.driver}), {len(info.joints)} joints, "
              f"mode {pb.RobotMode.Name(state.mode)}, q = {[round(v, 4) for v in q0]}")

        # 2. The lease, renewed at a third of its period by a heartbeat thread.
        lease = stub.AcquireLease(pb.AcquireLeaseRequest(client_name=args.name),
                                  metadata=metadata, timeout=5)
        period_s = lease.heartbeat_period_ns * 1e-9
        stop = threading.Event()

        def heartbeat():
            while not stop.wait(period_s / 3):
                stub.RenewLease(pb.RenewLeaseRequest(lease_id=lease.lease_id),
                                metadata=metadata, timeout=period_s)

        beat = threading.Thread(target=heartbeat, daemon=True)
        beat.start()
        print(f"lease {lease.lease_id[:8]}... held by {lease.holder}, heartbeat "
              f"{period_s * 1e3:.0f} ms")

        try:
            # 3. A short trajectory: the waist 0.1 rad towards the middle of its range and back.
            joint = 0
            limits = info.joints[joint]
            middle = 0.5 * (limits.min_position + limits.max_position)
            delta = 0.1 if q0[joint] <= middle else -0.1
            v_max, a_max = 0.5 * limits.max_velocity, 0.5 * limits.max_acceleration
            duration_s = max(abs(delta) * math.pi / (2 * v_max),
                             math.sqrt(abs(delta) * math.pi ** 2 / (2 * a_max)), 0.5)
            request = pb.ExecuteTrajectoryRequest(
                lease_id=lease.lease_id,
                trajectory_id=f"python-example-{os.getpid()}-{int(time.time())}")
            for t, q in cosine_samples(q0, joint, delta, duration_s, rate_hz=50):
                request.waypoints.add(time_from_start_ns=round(t * 1e9), q=q)
            ack = stub.ExecuteTrajectory(request, metadata=metadata, timeout=5)
            print(f"trajectory '{ack.trajectory_id}' accepted: {len(request.waypoints)} "
                  f"waypoints, {ack.duration_s:.3f} s")

            # 4. Wait until the server reports it finished.
            stream = stub.StreamState(pb.StreamStateRequest(rate_hz=50), metadata=metadata,
                                      timeout=ack.duration_s + 10)
            for state in stream:
                if state.last_trajectory_id == ack.trajectory_id:
                    break
            stream.cancel()
            status = pb.TrajectoryStatus.Name(state.last_trajectory_status)
            print(f"trajectory '{ack.trajectory_id}': {status}, q = "
                  f"{[round(v, 4) for v in state.q]}")
            if state.last_trajectory_status != pb.TRAJECTORY_STATUS_COMPLETED:
                print("not completed: " + state.last_trajectory_message, file=sys.stderr)
                return 1

            # 5. A plan: waypoints, not samples. PreviewPlan times and checks it as ExecutePlan
            #    would and answers the hash; ExecutePlan with that hash runs exactly that.
            q1 = list(state.q)
            via, stop_at = list(q1), list(q1)
            via[0] += 0.6 * delta
            via[1] += 0.04
            stop_at[0] += delta
            # No algorithm: the server's, named in the preview's answer.
            plan = pb.PlanMessage(
                plan_id=f"python-example-plan-{os.getpid()}-{int(time.time())}",
                velocity_scale=0.5, acceleration_scale=0.5)
            plan.waypoints.add(q=q1)
            plan.waypoints.add(q=via, via=True)  # passed through without stopping
            plan.waypoints.add(q=stop_at)
            plan.waypoints.add(q=q1, min_duration_s=0.5)  # back, in no less than 0.5 s
            preview = stub.PreviewPlan(pb.PreviewPlanRequest(plan=plan, with_samples=True),
                                       metadata=metadata, timeout=5)
            print(f"plan '{preview.plan_id}' previewed: {len(plan.waypoints)} waypoints, "
                  f"{preview.duration_s:.3f} s, {len(preview.samples)} samples at "
                  f"{preview.sample_rate_hz:g} Hz, {preview.algorithm}, hash "
                  f"{preview.plan_hash.hex()}")
            plan.algorithm = preview.algorithm
            plan.plan_hash = preview.plan_hash
            plan_ack = stub.ExecutePlan(pb.ExecutePlanRequest(lease_id=lease.lease_id, plan=plan),
                                        metadata=metadata, timeout=5)
            same = plan_ack.plan_hash == preview.plan_hash
            print(f"plan '{plan_ack.plan_id}' accepted: {plan.ByteSize()} bytes, "
                  f"{plan_ack.duration_s:.3f} s, hash {plan_ack.plan_hash.hex()} "
                  f"({'the previewed one' if same else 'NOT the previewed one'})")
            if not same:
                return 1
            stream = stub.StreamState(pb.StreamStateRequest(rate_hz=50), metadata=metadata,
                                      timeout=plan_ack.duration_s + 10)
            for state in stream:
                if state.last_trajectory_id == plan_ack.plan_id:
                    break
            stream.cancel()
            print(f"plan '{plan_ack.plan_id}': "
                  f"{pb.TrajectoryStatus.Name(state.last_trajectory_status)}, q = "
                  f"{[round(v, 4) for v in state.q]}")
            if state.last_trajectory_status != pb.TRAJECTORY_STATUS_COMPLETED:
                print("not completed: " + state.last_trajectory_message, file=sys.stderr)
                return 1

            # 6. The same plan with one bit of its hash flipped: not what was previewed, refused.
            tampered = pb.PlanMessage()
            tampered.CopyFrom(plan)
            tampered.plan_id = plan.plan_id + "-tampered"
            tampered.plan_hash = bytes([plan.plan_hash[0] ^ 1]) + plan.plan_hash[1:]
            try:
                stub.ExecutePlan(pb.ExecutePlanRequest(lease_id=lease.lease_id, plan=tampered),
                                 metadata=metadata, timeout=5)
                print("the plan with a tampered hash was accepted", file=sys.stderr)
                return 1
            except grpc.RpcError as refusal:
                print(f"plan with a tampered hash refused ({refusal.code().name}): "
                      f"{refusal.details()}")

            # 7. Into the table: the server checks the path against its workspace and refuses.
            if not info.workspace_yaml or info.model_name != "puma560":
                print("the server checks no PUMA 560 workspace: the colliding trajectory is "
                      "skipped (start it with --workspace data/workspaces/puma560_table.yaml)")
            else:
                into = pb.ExecuteTrajectoryRequest(
                    lease_id=lease.lease_id,
                    trajectory_id=f"python-example-table-{os.getpid()}-{int(time.time())}")
                for t, q in cosine_move(list(state.q), Q_INTO_TABLE, info.joints, rate_hz=50):
                    into.waypoints.add(time_from_start_ns=round(t * 1e9), q=q)
                try:
                    stub.ExecuteTrajectory(into, metadata=metadata, timeout=10)
                    print("the trajectory into the table was accepted", file=sys.stderr)
                    return 1
                except grpc.RpcError as refusal:
                    print(f"trajectory into the table refused ({refusal.code().name}): "
                          f"{refusal.details()}")
        finally:
            # 8. Give the lease back.
            stop.set()
            beat.join()
            stub.ReleaseLease(pb.ReleaseLeaseRequest(lease_id=lease.lease_id),
                              metadata=metadata, timeout=5)
            print("lease released")
    return 0


if __name__ == "__main__":
    sys.exit(main())
