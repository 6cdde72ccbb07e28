#!/usr/bin/env python3
"""Checks which folder may include which (the architecture, physics <- planner <-
server <- cli, and the physics stages of physics/CMakeLists.txt).

Usage: check_layout.py [REPO_ROOT]. Prints every include that breaks a rule and exits
1, or prints a one-line summary and exits 0. Run as the LayoutDependencies test.
"""
import os
import re
import sys

# Folder -> folders (project-relative prefixes) its sources may include.
STAGES = {
    "physics/core": [],
    "physics/table": ["physics/core"],
    "physics/motion": ["physics/core"],
    "physics/ode": ["physics/core"],
    "physics/impact": ["physics/core", "physics/ode"],
    "physics/events": ["physics/core", "physics/motion", "physics/table"],
    "physics/sim": ["physics/core", "physics/table", "physics/motion", "physics/impact",
                    "physics/events"],
    "planner": ["physics", "planner"],
    "server": ["physics", "planner", "server", "snooker/v1"],
    "cli": ["physics", "planner", "server", "cli", "snooker/v1"],
}
# System headers a folder must not use: the libraries never see gRPC or Protobuf.
FORBIDDEN_SYSTEM = {
    "physics": ["grpc", "grpcpp/", "google/protobuf/", "nlopt"],
    "planner": ["grpc", "grpcpp/", "google/protobuf/"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SYSTEM_INCLUDE = re.compile(r'^\s*#\s*include\s+<([^>]+)>', re.M)


def rules_for(path):
    best = None
    for folder in STAGES:
        if path.startswith(folder + "/") and (best is None or len(folder) > len(best)):
            best = folder
    return best


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    root = os.path.abspath(root)
    problems, checked = [], 0
    for top in ("physics", "planner", "server", "cli"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".h", ".cc")):
                    continue
                path = os.path.relpath(os.path.join(dirpath, name), root)
                folder = rules_for(path)
                if folder is None:
                    problems.append(f"{path}: in no declared folder (add it to STAGES)")
                    continue
                allowed = [folder] + STAGES[folder]
                with open(os.path.join(root, path), encoding="utf-8") as f:
                    text = f.read()
                for inc in SYSTEM_INCLUDE.findall(text):
                    checked += 1
                    for bad in FORBIDDEN_SYSTEM.get(top, []):
                        if inc.startswith(bad):
                            problems.append(f"{path}: includes <{inc}>, which {top}/ must not use")
                for inc in INCLUDE.findall(text):
                    checked += 1
                    if "/" not in inc:
                        continue  # a generated or same-folder header
                    if not any(inc.startswith(a + "/") for a in allowed):
                        problems.append(f"{path}: includes {inc}, outside {allowed}")
    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"layout ok: {checked} includes checked")
    return 0


if __name__ == "__main__":
    sys.exit(main())
