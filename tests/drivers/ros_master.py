#!/usr/bin/env python3
"""Debian's rosmaster on loopback, for the ROS 1 tests (a CTest fixture, and the restart test).

    ros_master.py start DIR   starts `rosmaster --core` on a free port, detached; writes
                              DIR/master_uri and DIR/master.pid once the master answers
    ros_master.py stop DIR    stops it (SIGINT, then SIGKILL) and removes the two files

ROS_IP=127.0.0.1 makes the master (and every node the tests start) advertise 127.0.0.1, not
the host name; ROS_HOME keeps its logs in DIR.
"""

import os
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client

ROSMASTER = "/usr/bin/rosmaster"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def loopback_environment(directory):
    env = dict(os.environ)
    env["ROS_IP"] = "127.0.0.1"
    env.pop("ROS_HOSTNAME", None)
    env["ROS_HOME"] = directory
    return env


def answers(uri, timeout_s=0.5):
    socket.setdefaulttimeout(timeout_s)
    try:
        code, _, _ = xmlrpc.client.ServerProxy(uri).getPid("/ros_master_py")
        return code == 1
    except (OSError, xmlrpc.client.Error):
        return False
    finally:
        socket.setdefaulttimeout(None)


def start_master(directory, port=None, wait_s=20.0):
    """Starts a master (on `port`, or a free one); returns (process, uri) once it answers."""
    os.makedirs(directory, exist_ok=True)
    port = port or free_port()
    uri = f"http://127.0.0.1:{port}"
    log = open(os.path.join(directory, f"rosmaster-{port}.log"), "ab")
    # Debian's ROS scripts need Debian's Python (TOOLCHAIN.md): not `env python3`.
    process = subprocess.Popen(["/usr/bin/python3", ROSMASTER, "--core", "-p", str(port)],
                               env=loopback_environment(directory), stdout=log, stderr=log,
                               stdin=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + wait_s
    while not answers(uri):
        if process.poll() is not None or time.monotonic() > deadline:
            process.kill()
            raise RuntimeError(f"rosmaster on port {port} did not start (log in {directory})")
        time.sleep(0.1)
    return process, uri


def stop_pid(pid):
    try:
        os.kill(pid, signal.SIGINT)
    except ProcessLookupError:
        return
    for _ in range(50):
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        time.sleep(0.1)
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("start", "stop"):
        sys.exit("usage: ros_master.py start|stop DIR")
    command, directory = sys.argv[1], sys.argv[2]
    uri_file, pid_file = (os.path.join(directory, name) for name in ("master_uri", "master.pid"))
    if command == "start":
        if os.path.exists(pid_file):  # a run that did not clean up
            stop_pid(int(open(pid_file).read()))
        process, uri = start_master(directory)
        with open(pid_file, "w") as f:
            f.write(str(process.pid))
        with open(uri_file, "w") as f:
            f.write(uri)
        print(f"rosmaster {uri} (pid {process.pid})")
    else:
        if os.path.exists(pid_file):
            stop_pid(int(open(pid_file).read()))
        for path in (uri_file, pid_file):
            if os.path.exists(path):
                os.remove(path)


if __name__ == "__main__":
    main()
