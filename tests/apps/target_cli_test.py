#!/usr/bin/python3
"""CTest: `telear capture --target` and `telear register --target` refuse bad input (exit 2,
one line naming the option and what was expected) before touching a server or a folder.

Usage: target_cli_test.py TELEAR_BINARY
"""

import subprocess
import sys
import tempfile


def run(telear, arguments):
    result = subprocess.run([telear] + arguments, capture_output=True, text=True, timeout=60)
    return result.returncode, result.stderr.strip()


def main():
    telear = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as folder:
        cases = [
            (["register", "--captures", folder, "--robot", "puma560", "--target",
              "charuco:5x5:0.03:0.04:4x4_50", "-o", folder + "/out.yaml"],
             "telear register: --target: target 'charuco:5x5:0.03:0.04:4x4_50': marker side "
             "0.04 m must be smaller than the square side 0.03 m (the marker sits inside a white "
             "square)"),
            (["register", "--observations", "obs.yaml", "--rig", "rig.yaml", "--target",
              "aruco:4x4_50:0:0.1", "-o", folder + "/out.yaml"],
             "telear register: --target: only with --captures (an observations file holds "
             "points, not images)"),
            (["capture", "--robot", "localhost:1", "--vision", "localhost:2", "--target",
              "qr:1", "-o", folder + "/capture"],
             "telear capture: --target: target 'qr:1': unknown kind 'qr'; expected "
             "aruco:DICT:ID:SIDE_M, apriltag:FAMILY:ID:SIDE_M or "
             "charuco:XxY:SQUARE_M:MARKER_M:DICT"),
            (["capture", "--robot", "localhost:1", "--vision", "localhost:2", "--target",
              "apriltag:36h12:0:0.1", "-o", folder + "/capture"],
             "telear capture: --target: target 'apriltag:36h12:0:0.1': unknown AprilTag family "
             "'36h12'"),
            (["capture", "--manual", "--robot", "localhost:1", "--vision", "localhost:2",
              "--target", "charuco:4x4:0.08:0.05:4x4_99", "-o", folder + "/capture"],
             "telear capture: --target: target 'charuco:4x4:0.08:0.05:4x4_99': unknown ArUco "
             "dictionary '4x4_99'"),
        ]
        for arguments, expected in cases:
            code, message = run(telear, arguments)
            if code != 2 or not message.startswith(expected):
                failures.append(f"{' '.join(arguments)}: exit {code}, {message!r}")
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
