#!/usr/bin/python3
"""CTest: `telear capture --manual`, the operator's capture at the terminal (issue 15).

Usage: capture_manual_cli_test.py TELEAR_BINARY DATA_DIR

`telear robot-server` (simulated PUMA 560) and `telear vision-server --source sim` run as
processes on loopback, as in capture_register_cli_test.py. `telear capture --manual` reads the
operator's commands from stdin: joint and Cartesian jogs, `a` (or an empty line) to add the
pose at rest, `s` to solve, `q` to finish. The capture folder it leaves is checked, solved with
`telear register --captures` and compared with the rig's true cameras by `telear eval`.
"""

import os
import re
import subprocess
import sys
import tempfile

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from capture_register_cli_test import lab_servers, registration_errors, run  # noqa: E402

# The operator's moves, each from the start pose (where both cameras see the marker) and back:
# joints by degrees as `j N D`, the tool along the base's axes by mm. Spread like the automatic
# poses (the arm turned by up to 35 deg, the wrist tilted and spun), inside the joint limits (the
# wrist's spin starts 33 deg below its upper limit): a pose that loses the marker is reported
# and kept, and does not enter the solve.
MOVES = [
    [("j", 1, 29), ("j", 5, 20)],
    [("j", 1, -29), ("j", 4, 35)],
    [("j", 2, 19), ("j", 6, 30)],
    [("j", 2, -19), ("j", 5, -20), ("j", 6, -60)],
    [("j", 3, 24), ("j", 4, -35)],
    [("j", 3, -24), ("j", 5, 25)],
    [("j", 1, 19), ("j", 2, -16), ("j", 4, 35), ("j", 6, 30)],
    [("j", 1, -19), ("j", 3, 19), ("j", 5, -25), ("j", 6, -45)],
    [("z", None, 90), ("j", 4, -35), ("j", 5, 25)],
    [("x", None, -90), ("j", 4, 35), ("j", 5, -25)],
    [("j", 2, 16), ("j", 3, -16), ("j", 6, -30)],
    [("j", 1, 24), ("j", 3, -19), ("j", 4, -30)],
    [("j", 1, -24), ("j", 2, 16), ("j", 5, 25), ("j", 6, 25)],
    [("y", None, 90), ("j", 5, -20), ("j", 6, -50)],
    [("z", None, -75), ("j", 4, 25)],
    [("j", 1, 35), ("j", 2, 13), ("j", 5, -25)],
    [("j", 1, -35), ("j", 3, -19), ("j", 6, 25)],
    [("j", 2, -22), ("j", 3, 22), ("j", 4, 30), ("j", 5, 20)],
    [("j", 2, 22), ("j", 3, -26), ("j", 4, -30), ("j", 6, -40)],
]


def mirrored(move):
    """The same arm move with the wrist turned the other way (its spin kept under the limit)."""
    return [(kind, joint, -delta if joint == 6 and -delta <= 30 else
             (30 if joint == 6 else -delta) if kind == "j" and joint >= 4 else delta)
            for kind, joint, delta in move]


MOVES += [mirrored(move) for move in MOVES]  # sigma ~2.1 mm with 15 seen poses: twice as many
POSES = len(MOVES) + 1  # and the start


def command(kind, joint, delta):
    return f"j {joint} {delta:+g}" if kind == "j" else f"{kind} {delta:+g}"


def operator_session():
    """stdin: add the start pose; each move, add, move back; a solve after 4 poses (too few:
    it says so and the capture goes on), a typo and a bad joint, an empty line as `a` once,
    the final solve, q."""
    lines = ["a"]
    for n, move in enumerate(MOVES):
        lines += [command(*step) for step in move]
        lines.append("" if n == 5 else "a")
        lines += [command(kind, joint, -delta) for kind, joint, delta in reversed(move)]
        if n == 2:
            lines += ["s", "j 9 +5", "hop"]
    return "\n".join(lines + ["s", "q"]) + "\n"


def main():
    telear, data = sys.argv[1], sys.argv[2]
    start_file = sys.argv[3] if len(sys.argv) > 3 else None
    failures = []
    calibration = os.path.join(data, "cameras", "puma560_stereo.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        captures = os.path.join(tmp, "captures")
        with lab_servers(telear, calibration, tmp, start_file) as (robot_address, vision_address, token):
            arguments = ["capture", "--manual", "--robot", robot_address, "--vision",
                         vision_address, "--token-file", token, "--arm", "puma560",
                         "--frames", "3", "--settle", "0.1", "-o", captures]
            r = subprocess.run([telear] + arguments, input=operator_session(), capture_output=True,
                               text=True, timeout=600)
            print(r.stdout)
            added = re.findall(r"^pose (\d+): 3 frames, marker (seen left and right|seen left "
                               r"only|seen right only|not seen)", r.stdout, re.M)
            both = sum(1 for _, seen in added if seen == "seen left and right")
            if r.returncode != 0:
                failures.append(f"capture --manual: status {r.returncode}, {r.stderr!r}")
            if not r.stdout.startswith("manual capture into " + captures):
                failures.append(f"no instructions first: {r.stdout[:200]!r}")
            if "  j N D      jog joint N (from 1)" not in r.stdout:
                failures.append("the commands are not listed")
            if [int(i) for i, _ in added] != list(range(POSES)):
                failures.append(f"added poses {added}")
            # Most, not all: a lease lapsing on a loaded machine stops a jog short.
            if both < POSES // 2:
                failures.append(f"the marker seen in both eyes at {both} of {POSES} poses")
            if "not solved: capture '" not in r.stdout:
                failures.append("the early solve (4 poses) did not say why it could not")
            if "uncertainty (1 sigma): base" not in r.stdout:
                failures.append("the final solve printed no registration")
            if "'j 9 +5': j N D with N 1..6 and D a number" not in r.stdout or \
                    "'hop': unknown command (h: the commands)" not in r.stdout:
                failures.append("bad commands were not explained")
            if not re.search(r"^jog: target( -?\d+\.\d\d){6} deg$", r.stdout, re.M):
                failures.append("no jog target printed")
            if not re.search(r"coverage: the marker found at \d+ \(left\) and \d+ \(right\) of "
                             rf"{POSES} poses", r.stdout) or \
                    not os.path.getsize(os.path.join(captures, "coverage.png")) > 1000:
                failures.append("no coverage image")
            if "register with: telear register --captures " + captures not in r.stdout:
                failures.append("the closing line does not say how to register")

            # The folder: capture_for_registration's format, one entry per added pose.
            manifest = {}
            if os.path.exists(os.path.join(captures, "capture.yaml")):
                with open(os.path.join(captures, "capture.yaml")) as f:
                    manifest = yaml.safe_load(f)
            if manifest.get("telear_capture") != 1 or manifest.get("robot") != "puma560" or \
                    manifest.get("cameras") != "cameras.yaml" or \
                    len(manifest.get("poses", [])) != POSES:
                failures.append(f"manifest {str(manifest)[:300]}")
            else:
                frame = manifest["poses"][3]["frames"][1]
                if frame["left"] != "pose_003/left_1.png" or \
                        not os.path.exists(os.path.join(captures, frame["right"])):
                    failures.append(f"pose 3's second frame {frame}")

            # Nothing added: exit 1 saying so; a used folder: refused before anything moves.
            empty = subprocess.run([telear] + arguments[:-1] + [os.path.join(tmp, "none")],
                                   input="q\n", capture_output=True, text=True, timeout=120)
            if empty.returncode != 1 or empty.stderr != (
                    "telear capture: no pose was added: nothing to register (" +
                    os.path.join(tmp, "none") + ")\n"):
                failures.append(f"nothing added: {empty.returncode} {empty.stderr!r}")
            used = subprocess.run([telear] + arguments, input="a\nq\n", capture_output=True,
                                  text=True, timeout=120)
            if used.returncode != 1 or "already holds a capture" not in used.stderr:
                failures.append(f"a used folder: {used.returncode} {used.stderr!r}")

        if not failures:
            registered = os.path.join(tmp, "registered.yaml")
            r = run(telear, ["register", "--captures", captures, "--robot", "puma560", "-o",
                             registered])
            if r.returncode != 0:
                failures.append(f"register: status {r.returncode}, {r.stdout!r} {r.stderr!r}")
            else:
                errors = registration_errors(telear, calibration, registered, tmp, failures)
                for eye, mm in errors.items():
                    print(f"manual capture, {eye} eye: registration {mm:.3f} mm")

    for failure in failures:
        print(failure, file=sys.stderr)
    if not failures:
        print("captured by hand through the servers and registered")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
