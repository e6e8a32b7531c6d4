#!/usr/bin/python3
"""CTest: register real cameras as a lab would, every program a process (issue 15).

Usage: capture_register_cli_test.py TELEAR_BINARY DATA_DIR

`telear robot-server` (simulated PUMA 560) and `telear vision-server --source sim` (the
simulated rig following the robot server, serving the rig's calibration) run on loopback;
`telear capture --poses auto:N` moves the arm and records a capture folder through them;
`telear register --captures DIR` solves the registration; `telear eval` compares it with the
rig's true cameras (its JSON). Bad input exits 2 with one line naming the problem.
"""

import contextlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile

import yaml


def start(telear, arguments):
    """Starts a server and returns (process, address) from its first stdout line."""
    server = subprocess.Popen([telear] + arguments, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    line = server.stdout.readline()
    match = re.fullmatch(r"(robot|vision) server listening on (\S+)\n", line)
    if not match:
        server.kill()
        raise AssertionError(f"{arguments[0]}: unexpected first line {line!r}")
    return server, match.group(2)


def run(telear, arguments, timeout=600):
    return subprocess.run([telear] + arguments, capture_output=True, text=True, timeout=timeout)


def start_pose(telear, tmp, start_file=None):
    """A configuration at which both cameras detect the marker (the operator's jog): from
    `start_file`, the CTest fixture puma560_marker_start's observations (tests/CMakeLists.txt),
    when it exists, else rendered here the same way."""
    observations = start_file
    if not observations or not os.path.exists(observations):
        observations = os.path.join(tmp, "find.yaml")
        r = run(telear, ["sim", "observations", "--configs", "4", "--seed", "2", "-o",
                         observations])
        assert r.returncode == 0, r.stderr
    with open(observations) as f:
        found = yaml.safe_load(f)
    for configuration in found["configurations"]:
        if configuration.get("left") and configuration.get("right"):
            return configuration["q"]
    raise AssertionError("the marker was not detected in both eyes anywhere")


@contextlib.contextmanager
def lab_servers(telear, calibration, tmp, start_file=None):
    """The lab's servers on loopback, sharing a token file: `telear robot-server` (the simulated
    PUMA 560 where both cameras see the marker) and `telear vision-server --source sim` (the rig
    following it, serving `calibration`). Yields (robot address, vision address, token file);
    both are stopped (SIGTERM) on leaving."""
    token = os.path.join(tmp, "token")
    with open(token, "w") as f:
        f.write("capture-test-token\n")
    q = ",".join(f"{v:.9f}" for v in start_pose(telear, tmp, start_file))
    robot, robot_address = start(telear, ["robot-server", "--listen", "127.0.0.1:0",
                                          "--token-file", token, "--q", q])
    vision = None
    try:
        vision, vision_address = start(
            telear, ["vision-server", "--listen", "127.0.0.1:0", "--source", "sim",
                     "--robot-server", robot_address, "--token-file", token,
                     "--calibration", calibration, "--fps", "10"])
        yield robot_address, vision_address, token
    finally:
        for server in (vision, robot):
            if server:
                server.send_signal(signal.SIGTERM)
                server.communicate(timeout=30)


def registration_errors(telear, truth, registered, tmp, failures):
    """`telear eval` of `registered` against `truth`: {eye: registration mm}, each checked
    against the 2 mm bound (a failure appended otherwise); empty when eval failed."""
    table = os.path.join(tmp, "eval.json")
    e = run(telear, ["eval", "--truth", truth, "--estimate", registered, "--configurations",
                     "10", "--json", table])
    if e.returncode != 0:
        failures.append(f"eval: {e.returncode} {e.stderr!r}")
        return {}
    with open(table) as f:
        accuracy = json.load(f)
    print(json.dumps(accuracy)[:2000])
    errors = {eye: accuracy[eye]["registration_mm"] for eye in ("left", "right")}
    for eye, mm in errors.items():
        if not mm < 2.0:
            failures.append(f"{eye} registration {mm} mm (bound 2 mm)")
    return errors


def main():
    telear, data = sys.argv[1], sys.argv[2]
    start_file = sys.argv[3] if len(sys.argv) > 3 else None
    failures = []
    calibration = os.path.join(data, "cameras", "puma560_stereo.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        with lab_servers(telear, calibration, tmp, start_file) as (robot_address, vision_address, token):
            captures = os.path.join(tmp, "captures")
            r = run(telear, ["capture", "--robot", robot_address, "--vision", vision_address,
                             "--token-file", token, "--arm", "puma560", "--poses", "auto:10",
                             "--frames", "2", "--speed", "1", "--settle", "0.1", "-o",
                             captures])
            coverage = os.path.join(captures, "coverage.png")
            if r.returncode != 0 or "pose 1/10" not in r.stdout or \
                    not re.search(r"coverage: the marker found at ([4-9]|10) \(left\) and "
                                  r"([4-9]|10) \(right\)", r.stdout) or \
                    not os.path.getsize(coverage) > 1000:
                failures.append(f"capture: status {r.returncode}, {r.stdout!r} {r.stderr!r}")
            else:
                print(r.stdout)
                if os.environ.get("TELEAR_TEST_OUTPUT"):  # to look at the coverage image
                    shutil.copy(coverage, os.environ["TELEAR_TEST_OUTPUT"])

            # Bad input: one line, exit 2.
            bad = run(telear, ["capture", "--robot", robot_address, "--vision", vision_address,
                               "--token-file", token, "--poses", "auto:x", "-o",
                               os.path.join(tmp, "bad")])
            expected = "telear capture: --poses 'auto:x': expected auto:N with N a number\n"
            if bad.returncode != 2 or bad.stderr != expected:
                failures.append(f"capture auto:x: {bad.returncode} {bad.stderr!r}")
            again = run(telear, ["capture", "--robot", robot_address, "--vision",
                                 vision_address, "--token-file", token, "--poses", "auto:3",
                                 "-o", captures])
            if again.returncode != 1 or "already holds a capture" not in again.stderr:
                failures.append(f"capture into a used folder: {again.returncode} "
                                f"{again.stderr!r}")

        if not failures:
            registered = os.path.join(tmp, "registered.yaml")
            r = run(telear, ["register", "--captures", captures, "--robot", "puma560", "-o",
                             registered])
            if r.returncode != 0 or "bundle adjustment" not in r.stdout or \
                    "uncertainty (1 sigma): base" not in r.stdout:
                failures.append(f"register: status {r.returncode}, {r.stdout!r} {r.stderr!r}")
            else:
                print(r.stdout)
                registration_errors(telear, calibration, registered, tmp, failures)

            empty = os.path.join(tmp, "empty")
            os.makedirs(empty)
            r = run(telear, ["register", "--captures", empty, "--robot", "puma560", "-o",
                             os.path.join(tmp, "x.yaml")])
            if r.returncode != 2 or not r.stderr.startswith("telear register: capture '") or \
                    r.stderr.count("\n") != 1:
                failures.append(f"register of an empty folder: {r.returncode} {r.stderr!r}")
            r = run(telear, ["register", "--captures", captures, "--observations", "o.yaml",
                             "-o", os.path.join(tmp, "x.yaml")])
            if r.returncode != 2 or r.stderr != ("telear register: --captures and "
                                                 "--observations: give one of them\n"):
                failures.append(f"register with both inputs: {r.returncode} {r.stderr!r}")

    for failure in failures:
        print(failure, file=sys.stderr)
    if not failures:
        print("captured through the servers and registered")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
