#!/usr/bin/python3
"""CTest: runs examples/python/robot_example.py against a real `telear robot-server`.

Usage: robot_python_example_test.py TELEAR_BINARY EXAMPLE_SCRIPT WORKSPACE_YAML

Starts the server on 127.0.0.1:0 with a fresh token file, reads the bound port from its
"robot server listening on HOST:PORT" line, runs the example with /usr/bin/python3, then
stops the server with SIGTERM and checks that it shut down cleanly (exit status 0). The
server checks collisions against the PUMA's table (--workspace): the example's trajectory
into the table must be refused with the contact named.
"""

import os
import re
import signal
import subprocess
import sys
import tempfile


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
