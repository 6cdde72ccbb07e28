#!/usr/bin/env python3
"""Checks the tree's shape, each a test of its own:

  deps       which folder may include which (the architecture, physics <- planner <-
             server <- cli and physics <- calibration, and the physics stages of
             physics/CMakeLists.txt);
  functions  no function in physics/, planner/, calibration/, server/ or cli/ longer than
             MAX_FUNCTION_LINES (a longer one is phases that want names); needs
             Universal Ctags;
  text       product files (code, proto, README, docs) carry no issue numbers or
             development history, point at nothing outside the repository, and every
             docs/*.md they name exists.

Usage: check_layout.py [--check deps|functions|text] [REPO_ROOT] (default: deps).
Prints every problem and exits 1, or prints a one-line summary and exits 0. Run as
the LayoutDependencies, LayoutFunctionLength and ProductTextSelfContained tests.
"""
import json
import os
import re
import shutil
import subprocess
import sys

# Folder -> folders (project-relative prefixes) its sources may include.
STAGES = {
    "physics/core": [],
    "physics/table": ["physics/core"],
    "physics/motion": ["physics/core"],
    "physics/cue": ["physics/core"],
    "physics/ode": ["physics/core"],
    "physics/impact": ["physics/core", "physics/ode"],
    "physics/events": ["physics/core", "physics/motion", "physics/table"],
    "physics/sim": ["physics/core", "physics/table", "physics/motion", "physics/impact",
                    "physics/events"],
    "physics/model": ["physics/core", "physics/impact", "physics/sim", "physics/cue", "physics/table",
                      "physics/motion", "physics/events", "physics/ode"],
    "planner": ["physics", "planner"],
    "calibration": ["physics", "calibration"],
    "server": ["physics", "planner", "calibration", "server", "snooker/v1"],
    "cli": ["physics", "planner", "calibration", "server", "cli", "snooker/v1"],
}
# System headers a folder must not use: the libraries never see gRPC, Protobuf or
# HTTP (cpp-httplib, OpenSSL: the server's HTTP listener, server/http_server.cc).
FORBIDDEN_SYSTEM = {
    "physics": ["grpc", "grpcpp/", "google/protobuf/", "nlopt", "httplib.h", "openssl/"],
    "planner": ["grpc", "grpcpp/", "google/protobuf/", "httplib.h", "openssl/"],
    "calibration": ["grpc", "grpcpp/", "google/protobuf/", "httplib.h", "openssl/"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SYSTEM_INCLUDE = re.compile(r'^\s*#\s*include\s+<([^>]+)>', re.M)


def rules_for(path):
    best = None
    for folder in STAGES:
        if path.startswith(folder + "/") and (best is None or len(folder) > len(best)):
            best = folder
    return best


def check_deps(root):
    problems, checked = [], 0
    for top in ("physics", "planner", "calibration", "server", "cli"):
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



CODE_FOLDERS = ("physics", "planner", "calibration", "server", "cli")
MAX_FUNCTION_LINES = 120


def code_files(root):
    for top in CODE_FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if name.endswith((".h", ".cc")):
                    yield os.path.join(dirpath, name)


def check_functions(root):
    ctags = shutil.which("ctags")
    if ctags is None:
        print("Universal Ctags is not installed (Debian: universal-ctags)")
        return 1
    files = list(code_files(root))
    out = subprocess.run([ctags, "--output-format=json", "--fields=+ne", "--kinds-c++=f", "-o", "-"] + files,
                         check=True, capture_output=True, text=True).stdout
    problems, checked = [], 0
    for line in out.splitlines():
        tag = json.loads(line)
        if "end" not in tag:
            continue
        checked += 1
        length = tag["end"] - tag["line"] + 1
        if length > MAX_FUNCTION_LINES:
            path = os.path.relpath(tag["path"], root)
            problems.append(f"{path}:{tag['line']}: {tag['name']} is {length} lines (at most {MAX_FUNCTION_LINES})")
    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"functions ok: {checked} functions of at most {MAX_FUNCTION_LINES} lines")
    return 0


# Product text: what a user reads. docs/data holds measured data files.
TEXT_TOPS = CODE_FOLDERS + ("proto", "docs", "README.md")
TEXT_SUFFIXES = (".h", ".cc", ".proto", ".md", ".txt")
HISTORY = re.compile(r"\b(issue|ticket)[ -]?#?\d+|\b(before|after|since) (the )?issue\b", re.I)
OUTSIDE = re.compile(r"\.\./shared|shared/(seed|physics-notes|planning-notes)|(?<!docs/)\b(physics|planning)-notes\b(?!\.md)")
DOC_LINK = re.compile(r"\bdocs/([A-Za-z0-9_.-]+\.md)\b")


def text_files(root):
    for top in TEXT_TOPS:
        path = os.path.join(root, top)
        if os.path.isfile(path):
            yield path
            continue
        for dirpath, _, files in os.walk(path):
            if os.path.relpath(dirpath, root).startswith(os.path.join("docs", "data")):
                continue
            for name in sorted(files):
                if name.endswith(TEXT_SUFFIXES):
                    yield os.path.join(dirpath, name)


def check_text(root):
    problems, checked = [], 0
    for path in text_files(root):
        rel = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                checked += 1
                if HISTORY.search(line):
                    problems.append(f"{rel}:{number}: development history (history belongs to git): {line.strip()}")
                if OUTSIDE.search(line):
                    problems.append(f"{rel}:{number}: points outside the repository: {line.strip()}")
                for doc in DOC_LINK.findall(line):
                    if not os.path.isfile(os.path.join(root, "docs", doc)):
                        problems.append(f"{rel}:{number}: names docs/{doc}, which does not exist")
    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"text ok: {checked} lines checked")
    return 0


def main():
    args = sys.argv[1:]
    check = "deps"
    if len(args) >= 2 and args[0] == "--check":
        check, args = args[1], args[2:]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    checks = {"deps": check_deps, "functions": check_functions, "text": check_text}
    if check not in checks:
        print(f"unknown check {check!r}: one of {', '.join(checks)}")
        return 2
    return checks[check](root)


if __name__ == "__main__":
    sys.exit(main())
