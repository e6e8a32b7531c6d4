#!/usr/bin/python3
"""CTest: runs examples/python/robot_example.py against a real `telear robot-server`.

Usage: robot_python_example_test.py TELEAR_BINARY EXAMPLE_SCRIPT WORKSPACE_YAML

Starts the server on 127.0.0.1:0 with a fresh token file, reads the bound port from its
"robot server listening on HOST:PORT" line, runs the example with /usr/bin/python3, then
stops the server with SIGTERM and checks that it shut down cleanly (exit status 0). The
server checks collisions against the PUMA's table (--workspace): the example's trajectory
into the table must be refused with the contact named. The example's plan must be previewed
(a hash), executed with that hash to completion, and refused with a tampered hash.
"""

import os
import re
import signal
import subprocess
import sys
import tempfile


def check_plan(out):
    """The plan: previewed (hash), executed with that hash, completed; a tampered hash refused."""
    preview = re.search(r"plan '(\S+)' previewed: 4 waypoints, ([\d.]+) s, (\d+) samples at "
                        r"100 Hz, telear-blend-\d+, hash ([0-9a-f]{64})\n", out)
    if not preview:
        print("the example did not print the plan's preview", file=sys.stderr)
        return False
    plan_id, duration, hash_hex = preview.group(1), preview.group(2), preview.group(4)
    # 100 Hz samples from 0 to the duration, both ends included (the duration is rounded).
    if abs(int(preview.group(3)) - float(duration) * 100) > 2.1:
        print(f"{preview.group(3)} samples for {duration} s at 100 Hz", file=sys.stderr)
        return False
    accepted = re.search(r"plan '" + re.escape(plan_id) + r"' accepted: \d+ bytes, " +
                         re.escape(duration) + r" s, hash " + hash_hex +
                         r" \(the previewed one\)\n", out)
    completed = f"plan '{plan_id}': TRAJECTORY_STATUS_COMPLETED" in out
    tampered = bytes([bytes.fromhex(hash_hex)[0] ^ 1]).hex() + hash_hex[2:]
    refused = (f"plan with a tampered hash refused (INVALID_ARGUMENT): plan '{plan_id}-tampered' "
               f"rejected: its hash does not match: the client's is '{tampered}', the server's "
               f"is '{hash_hex}'") in out
    for ok, what in ((accepted, "accepted with the previewed hash"), (completed, "completed"),
                     (refused, "its tampered copy refused with both hashes")):
        if not ok:
            print(f"the example's plan was not {what}", file=sys.stderr)
            return False
    return True


def main():
    telear, example, workspace = sys.argv[1], sys.argv[2], sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        token_file = os.path.join(tmp, "token")
        with open(token_file, "w") as f:
            f.write("python-example-token\n")
        server = subprocess.Popen(
            [telear, "robot-server", "--listen", "127.0.0.1:0", "--token-file", token_file,
             "--workspace", workspace],
            stdout=subprocess.PIPE, text=True)
        try:
            line = server.stdout.readline()
            match = re.fullmatch(r"robot server listening on (\S+)\n", line)
            if not match:
                print("unexpected first line from the server: " + repr(line), file=sys.stderr)
                return 1
            example_run = subprocess.run(
                ["/usr/bin/python3", example, "--address", match.group(1), "--token-file",
                 token_file], timeout=60, stdout=subprocess.PIPE, text=True)
            print(example_run.stdout)
            if example_run.returncode != 0:
                print(f"the example failed with status {example_run.returncode}", file=sys.stderr)
                return 1
            if not check_plan(example_run.stdout):
                return 1
            expected = re.search(r"trajectory into the table refused \(INVALID_ARGUMENT\): "
                                 r".*trajectory collides: at t=\S+ s link '\w+' touches "
                                 r"'table_top' \(depth ", example_run.stdout)
            if not expected:
                print("the example did not print the server's collision refusal", file=sys.stderr)
                return 1
        finally:
            server.send_signal(signal.SIGTERM)
            status = server.wait(timeout=10)
        if status != 0:
            print(f"the server exited with status {status} after SIGTERM", file=sys.stderr)
            return 1
    print("robot example passed; the server shut down cleanly")
    return 0


if __name__ == "__main__":
    sys.exit(main())
