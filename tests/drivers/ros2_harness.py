"""Processes for the ROS 2 driver's tests: the Cyclone DDS test peer (ros2_test_peer.cpp, a
ros2_control arm as DDS sees one) and `telear robot-server --driver ros2`, with the gRPC client of
ros1_harness.py (its RobotServer's calls, started here with the ROS 2 driver's arguments).

Discovery stays on loopback: every process gets a CYCLONEDDS_URI that binds Cyclone DDS to `lo`,
turns multicast off and finds peers by unicast to 127.0.0.1 (a participant index per process),
and each test holds a domain of its own (Domain) so that cases running side by side never meet.
"""

import fcntl
import json
import os
import random
import subprocess
import tempfile

import ros1_harness as h
from ros1_harness import monotonic_ns, wait_for  # noqa: F401  (re-exported for the tests)

PUMA_JOINTS = h.PUMA_JOINTS

# Cyclone DDS 0.10's configuration (its docs/manual/options.md): General/Interfaces selects the
# network interface, General/AllowMulticast false keeps discovery and data unicast, and
# Discovery/Peers lists where to send participant announcements; ParticipantIndex auto gives
# each participant on the host its own unicast port, which is how peers on 127.0.0.1 find it.
LOOPBACK_CONFIG = (
    '<CycloneDDS><Domain id="any">'
    '<General><Interfaces><NetworkInterface name="lo"/></Interfaces>'
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
    '<Peers><Peer address="127.0.0.1"/></Peers></Discovery>'
    "</Domain></CycloneDDS>")


class Domain:
    """A DDS domain for one test, away from 0 (ROS 2's default): a random one of 100..230 (ROS
    allows 0..232) that no other test holds. Held by an flock on a file per domain, so tests
    running side by side never share one (two random picks alone collide often enough to
    show); the lock goes with the process."""

    DIRECTORY = os.path.join(tempfile.gettempdir(), "telear-ros2-domains")

    def __init__(self):
        os.makedirs(self.DIRECTORY, exist_ok=True)
        candidates = list(range(100, 231))
        random.shuffle(candidates)
        for domain in candidates:
            lock = open(os.path.join(self.DIRECTORY, f"{domain}.lock"), "w")
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                lock.close()
                continue
            self.id, self._lock = domain, lock
            return
        raise AssertionError("no free DDS domain in 100..230 for this test")

    def release(self):
        self._lock.close()


def loopback_environment(directory):
    env = dict(os.environ)
    env["CYCLONEDDS_URI"] = LOOPBACK_CONFIG
    env.pop("ROS_DOMAIN_ID", None)  # the domain is always given on the command line
    env["HOME"] = directory
    return env


class Peer:
    """The test peer as a process; its JSON log read back as a list of events."""

    def __init__(self, binary, domain, directory, joints=PUMA_JOINTS, initial=None, extra=()):
        self.log_path = os.path.join(directory, f"peer-{monotonic_ns()}.jsonl")
        self.silent_file = self.log_path + ".silent"
        args = [binary, "--domain", str(domain), "--joints", ",".join(joints),
                "--log", self.log_path, "--silent-file", self.silent_file]
        if initial is not None:
            args += ["--initial", ",".join(repr(v) for v in initial)]
        args += list(extra)
        self.stderr = open(self.log_path + ".stderr", "wb")
        self.process = subprocess.Popen(args, env=loopback_environment(directory),
                                        stdout=subprocess.PIPE, stderr=self.stderr, text=True)
        line = self.process.stdout.readline()
        if line.strip() != "peer ready":
            raise AssertionError(f"the test peer did not start: {line!r}")

    def events(self, kind=None):
        if not os.path.exists(self.log_path):
            return []
        with open(self.log_path) as f:
            # The peer may be writing a line right now: only whole lines count.
            lines = f.read().split("\n")[:-1]
        events = [json.loads(line) for line in lines if line.strip()]
        return [e for e in events if kind is None or e["event"] == kind]

    def trajectories(self):
        return self.events("trajectory")

    def set_silent(self, silent):
        if silent:
            open(self.silent_file, "w").close()
        elif os.path.exists(self.silent_file):
            os.remove(self.silent_file)

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(2)
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.stderr.close()


class RobotServer(h.RobotServer):
    """`telear robot-server --driver ros2 --ros-domain N` as a process, and ros1_harness's gRPC
    client of it (its calls: info, state, acquire, plan, preview, execute, ...)."""

    def __init__(self, telear, domain, directory, extra=(), robot="puma560"):
        self.token = "ros2-test-token"
        token_file = os.path.join(directory, "token")
        with open(token_file, "w") as f:
            f.write(self.token + "\n")
        self.err_path = os.path.join(directory, f"robot-server-{monotonic_ns()}.err")
        self.err = open(self.err_path, "wb")
        args = [telear, "robot-server", "--driver", "ros2", "--ros-domain", str(domain),
                "--robot", robot, "--listen", "127.0.0.1:0", "--token-file", token_file]
        self.process = subprocess.Popen(args + list(extra), env=loopback_environment(directory),
                                        stdout=subprocess.PIPE, stderr=self.err, text=True)
        line = self.process.stdout.readline()
        prefix = "robot server listening on "
        if not line.startswith(prefix):
            self._beat_stop = h.threading.Event()
            self.stop()
            raise AssertionError(f"robot-server did not start: {line!r}; stderr: "
                                 f"{open(self.err_path).read()}")
        self.address = line[len(prefix):].strip()
        self.channel = h.grpc.insecure_channel(self.address)
        self.stub = h.pb_grpc.RobotServiceStub(self.channel)
        self.metadata = [("authorization", "Bearer " + self.token),
                         ("telear-client", "ros2-test")]
        self.lease = None
        self._beat_stop = h.threading.Event()
        self._beat = None
