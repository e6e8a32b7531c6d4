"""Processes for the ROS 1 driver's tests and measurements: the test controller (a real actionlib
FollowJointTrajectory server, ros1_test_controller.cpp), `telear robot-server --driver ros1`, and a
gRPC client of that server (stubs generated from proto/ at run time, as the Python example does).
"""

import atexit
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(SOURCE_DIR, "examples", "python"))
sys.path.insert(0, HERE)

import grpc  # noqa: E402  (python3-grpcio)
import robot_example  # noqa: E402
import ros_master  # noqa: E402

PUMA_JOINTS = ["waist", "shoulder", "elbow", "wrist_roll", "wrist_bend", "wrist_swivel"]

_stubs_dir = tempfile.mkdtemp(prefix="telear-stubs-")
# Removed at exit: each CTest entry is its own interpreter, and 2,400 of these were left in /tmp.
atexit.register(shutil.rmtree, _stubs_dir, True)
pb, pb_grpc = robot_example.load_stubs(_stubs_dir)


def monotonic_ns():
    # CLOCK_MONOTONIC: the clock telear's servers and the test controller stamp with.
    return time.clock_gettime_ns(time.CLOCK_MONOTONIC)


def wait_for(predicate, timeout_s, what):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.02)
    raise AssertionError(f"timed out after {timeout_s} s waiting for {what}")


class Controller:
    """The test controller as a process; its JSON log read back as a list of events."""

    def __init__(self, binary, master_uri, directory, joints=PUMA_JOINTS, initial=None,
                 extra=()):
        self.log_path = os.path.join(directory, f"controller-{monotonic_ns()}.jsonl")
        self.silent_file = self.log_path + ".silent"
        args = [binary, "--joints", ",".join(joints), "--log", self.log_path,
                "--silent-file", self.silent_file]
        if initial is not None:
            args += ["--initial", ",".join(repr(v) for v in initial)]
        args += list(extra)
        env = ros_master.loopback_environment(directory)
        env["ROS_MASTER_URI"] = master_uri
        self.stderr = open(self.log_path + ".stderr", "wb")
        self.process = subprocess.Popen(args, env=env, stdout=subprocess.PIPE,
                                        stderr=self.stderr, text=True)
        line = self.process.stdout.readline()
        if line.strip() != "controller ready":
            raise AssertionError(f"the test controller did not start: {line!r}")

    def events(self, kind=None):
        if not os.path.exists(self.log_path):
            return []
        with open(self.log_path) as f:
            text = f.read()
        # The controller may be writing its next event: a last line without its newline is
        # not complete yet (its buffer reaches the file in pieces), and is read next time.
        complete = text[:text.rfind("\n") + 1]
        events = [json.loads(line) for line in complete.splitlines() if line.strip()]
        return [e for e in events if kind is None or e["event"] == kind]

    def set_silent(self, silent):
        if silent:
            open(self.silent_file, "w").close()
        elif os.path.exists(self.silent_file):
            os.remove(self.silent_file)

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(2)  # SIGINT: roscpp's own shutdown
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.stderr.close()


class RobotServer:
    """`telear robot-server` (by default --driver ros1) as a process, and a gRPC client of it."""

    def __init__(self, telear, master_uri, directory, extra=(), robot="puma560",
                 driver_args=None):
        """driver_args: the --driver options; None: ROS 1 on master_uri."""
        self.token = "ros1-test-token"
        token_file = os.path.join(directory, "token")
        with open(token_file, "w") as f:
            f.write(self.token + "\n")
        self.err_path = os.path.join(directory, f"robot-server-{monotonic_ns()}.err")
        self.err = open(self.err_path, "wb")
        env = ros_master.loopback_environment(directory)
        if driver_args is None:
            driver_args = ["--driver", "ros1", "--ros-master", master_uri]
        args = [telear, "robot-server"] + list(driver_args) + [
            "--robot", robot, "--listen", "127.0.0.1:0", "--token-file", token_file]
        self.process = subprocess.Popen(args + list(extra), env=env, stdout=subprocess.PIPE,
                                        stderr=self.err, text=True)
        line = self.process.stdout.readline()
        prefix = "robot server listening on "
        if not line.startswith(prefix):
            self.stop()
            raise AssertionError(f"robot-server did not start: {line!r}; stderr: "
                                 f"{open(self.err_path).read()}")
        self.address = line[len(prefix):].strip()
        self.channel = grpc.insecure_channel(self.address)
        self.stub = pb_grpc.RobotServiceStub(self.channel)
        self.metadata = [("authorization", "Bearer " + self.token),
                         ("telear-client", "ros1-test")]
        self.lease = None
        self._beat_stop = threading.Event()
        self._beat = None

    def call(self, name, request, timeout=5):
        return getattr(self.stub, name)(request, metadata=self.metadata, timeout=timeout)

    def info(self):
        return self.call("GetInfo", pb.GetInfoRequest())

    def state(self, rate_hz=100):
        stream = self.stub.StreamState(pb.StreamStateRequest(rate_hz=rate_hz),
                                       metadata=self.metadata)
        try:
            return next(stream)
        finally:
            stream.cancel()

    def wait_state(self, predicate, timeout_s, what):
        return wait_for(lambda: (lambda s: s if predicate(s) else None)(self.state()),
                        timeout_s, what)

    def acquire(self, heartbeat_ns=1_000_000_000, renew=True):
        """The lease, renewed at a third of its period by a thread. 1 s by default: the
        server's 250 ms leaves a Python renewal thread on a loaded 2-core machine too little
        room (a lapse is tested on purpose with a short period)."""
        self.lease = self.call("AcquireLease", pb.AcquireLeaseRequest(
            client_name="ros1-test", heartbeat_period_ns=heartbeat_ns))
        if renew:
            period_s = self.lease.heartbeat_period_ns * 1e-9
            self._beat_stop.clear()

            def beat():
                while not self._beat_stop.wait(period_s / 3):
                    self.lease = self.call("RenewLease",
                                           pb.RenewLeaseRequest(lease_id=self.lease.lease_id))

            self._beat = threading.Thread(target=beat, daemon=True)
            self._beat.start()
        return self.lease

    def stop_heartbeat(self):
        """Stops renewing; returns the server-clock time the lease then lapses (expires_ns)."""
        self._beat_stop.set()
        if self._beat:
            self._beat.join()
        return self.lease.expires_ns

    def plan(self, plan_id, waypoints, velocity_scale=0.5):
        message = pb.PlanMessage(plan_id=plan_id, velocity_scale=velocity_scale,
                                 acceleration_scale=0.5)
        for q in waypoints:
            message.waypoints.add(q=q)
        return message

    def preview(self, plan):
        return self.call("PreviewPlan", pb.PreviewPlanRequest(plan=plan, with_samples=True))

    def execute(self, plan, preview):
        plan.algorithm = preview.algorithm
        plan.plan_hash = preview.plan_hash
        return self.call("ExecutePlan",
                         pb.ExecutePlanRequest(lease_id=self.lease.lease_id, plan=plan))

    def log_text(self):
        self.err.flush()
        with open(self.err_path) as f:
            return f.read()

    def stop(self):
        self._beat_stop.set()
        if self.process.poll() is None:
            self.process.send_signal(2)
            try:
                self.process.wait(15)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.err.close()
