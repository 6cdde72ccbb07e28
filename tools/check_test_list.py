#!/usr/bin/env python3
"""Checks that every value-parametrized test names its parameter readably.

gtest shows a parameter it has no printer for as its bytes ("48-byte object <E8-2E
...>"), in --gtest_list_tests and in the line of a failure, where the reader needs the
case. Each parameter type gets a PrintTo beside its struct. This runs each test binary
given with --gtest_list_tests and fails on any parameter shown as bytes.

Usage: check_test_list.py TEST_BINARY... Prints every such test and exits 1, or a
one-line summary and exits 0. Run as the TestParametersPrintReadably test.
"""
import subprocess
import sys


def unreadable(binary):
    listing = subprocess.run([binary, "--gtest_list_tests"], capture_output=True, text=True,
                             timeout=60, check=True).stdout
    suite, found, tests = "", [], 0
    for line in listing.splitlines():
        if not line.startswith(" "):
            suite = line.split("#")[0].strip()
            continue
        tests += 1
        name, _, comment = line.strip().partition("#")
        if "-byte object <" in comment:
            found.append(f"{binary}: {suite}{name.strip()}: GetParam() printed as bytes")
    return found, tests


def main(binaries):
    if not binaries:
        print(__doc__.strip().splitlines()[-2], file=sys.stderr)
        return 2
    problems, tests = [], 0
    for binary in binaries:
        found, count = unreadable(binary)
        problems += found
        tests += count
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} tests show their parameter as bytes: give its type a PrintTo")
        return 1
    print(f"{tests} tests in {len(binaries)} binaries: every parameter printed readably")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
