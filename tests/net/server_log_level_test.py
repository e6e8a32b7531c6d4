#!/usr/bin/python3
"""CTest: --log-level on `telear robot-server` and `telear vision-server`, run as processes.

Usage: server_log_level_test.py TELEAR_BINARY

For each server: started on 127.0.0.1:0 at the default level (info) its stderr has spdlog's
"[info]" lines (the listening line at least); started with --log-level warn it has none; both
shut down cleanly on SIGTERM. A bad level is a usage error: exit 2 and one line naming the value
and the accepted words.
"""

import os
import re
import signal
import subprocess
import sys
import tempfile

ACCEPTED = "trace, debug, info, warn, error, off"


def run_server(telear, arguments):
    """Starts the server, waits for its ready line, stops it; returns (status, stderr)."""
    server = subprocess.Popen([telear] + arguments, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    try:
        line = server.stdout.readline()
        if not re.fullmatch(r"(robot|vision) server listening on \S+\n", line):
            raise AssertionError(f"{arguments[0]}: unexpected first line {line!r}")
    finally:
        server.send_signal(signal.SIGTERM)
        _, err = server.communicate(timeout=20)
    return server.returncode, err


def main():
    telear = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        token_file = os.path.join(tmp, "token")
        with open(token_file, "w") as f:
            f.write("log-level-test-token\n")
        return check(telear, {
            "robot-server": ["robot-server", "--listen", "127.0.0.1:0", "--token-file",
                             token_file],
            "vision-server": ["vision-server", "--listen", "127.0.0.1:0", "--source",
                              "synthetic", "--resolution", "64x48", "--fps", "10"],
        })


def check(telear, servers):
    failures = []
    for name, arguments in servers.items():
        status, err = run_server(telear, arguments)
        if status != 0 or "[info]" not in err:
            failures.append(f"{name} at the default level: status {status}, no [info] line in "
                            f"{err!r}")
        status, err = run_server(telear, arguments + ["--log-level", "warn"])
        if status != 0 or "[info]" in err:
            failures.append(f"{name} --log-level warn: status {status}, stderr {err!r}")
        bad = subprocess.run([telear] + arguments + ["--log-level", "loud"], capture_output=True,
                             text=True, timeout=20)
        expected = (f"telear {name}: --log-level 'loud' is not a log level; use one of "
                    f"{ACCEPTED}\n")
        if bad.returncode != 2 or bad.stderr != expected:
            failures.append(f"{name} --log-level loud: status {bad.returncode}, stderr "
                            f"{bad.stderr!r}, expected status 2 and {expected!r}")
    for failure in failures:
        print(failure, file=sys.stderr)
    if not failures:
        print("both servers honour --log-level")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
