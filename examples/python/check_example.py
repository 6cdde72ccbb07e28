#!/usr/bin/python3
"""CI check: the Python example client against the real `snooker serve` binary.

Starts `snooker serve --address 127.0.0.1:0`, reads the port it prints, runs
snooker_client.py against it, stops the server with SIGTERM and checks that it
exited cleanly and logged the example's calls. Exit 0 when all of that holds.

    /usr/bin/python3 examples/python/check_example.py --snooker build/cli/snooker \
        --stubs build/examples/python_stubs
"""
import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--snooker", required=True, help="the snooker binary")
    ap.add_argument("--stubs", required=True, help="folder of the generated Python stubs")
    args = ap.parse_args()
    try:
        import grpc  # noqa: F401  (python3-grpcio)
        import google.protobuf  # noqa: F401  (python3-protobuf)
    except ImportError as e:
        print("check_example: %s: install python3-grpcio and python3-protobuf "
              "(scripts/dev does)" % e, file=sys.stderr)
        return 1

    log = tempfile.TemporaryFile(mode="w+")
    server = subprocess.Popen([args.snooker, "serve", "--address", "127.0.0.1:0"],
                              stdout=subprocess.PIPE, stderr=log, text=True)
    try:
        first = server.stdout.readline()
        m = re.search(r"on port (\d+)", first)
        if not m:
            print("check_example: the server did not start: %r" % first, file=sys.stderr)
            return 1
        client = os.path.join(os.path.dirname(os.path.abspath(__file__)), "snooker_client.py")
        rc = subprocess.run([sys.executable, client, "--target", "127.0.0.1:" + m.group(1),
                             "--stubs", args.stubs], timeout=60).returncode
    finally:
        server.send_signal(signal.SIGTERM)
        try:
            server_rc = server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
            server_rc = "killed after 30 s"
    log.seek(0)
    calls = re.findall(r"method=(\w+) .*? status=(\w+)", log.read())
    print("server exit status:", server_rc, "; calls logged:", calls)
    ok = (rc == 0 and server_rc == 0 and ("GetModel", "OK") in calls and ("Simulate", "OK") in calls
          and ("Simulate", "INVALID_ARGUMENT") in calls and ("Plan", "OK") in calls
          and ("PlanStream", "OK") in calls and ("Plan", "INVALID_ARGUMENT") in calls)
    print("check_example:", "passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
