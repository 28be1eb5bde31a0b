#!/usr/bin/python3
"""docs/architecture.md's folder table matches the tree.

  tests/architecture_folders.py [SOURCE_DIR]
  tests/architecture_folders.py --self-test

Reads the table of the section "## Source layout" of docs/architecture.md: every row whose first
cell is a backticked folder (`sim/eda/sta/`) names that folder. Fails, naming each, when
 - a named folder does not exist, or
 - a folder holding sources is not named: any folder under sim/ (at any depth) with a source file
   directly in it, and any top-level folder with a source file anywhere below it.
A source file is one with a source extension (SOURCE_EXTENSIONS) or an executable script (#!).
The files are git's (tracked and untracked but not ignored) when SOURCE_DIR is a git work tree,
else every file under it; hidden folders and build outputs are skipped.
The self-test copies the table into a temporary tree built to match it, checks that it passes,
then removes a named folder and adds an unnamed one, and checks that each is reported.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

DOC = "docs/architecture.md"
SECTION = "## Source layout"
SOURCE_EXTENSIONS = {".h", ".hpp", ".cpp", ".cc", ".c", ".sv", ".svh", ".v", ".vlt", ".py",
                     ".sh", ".cmake", ".tcl", ".ys", ".f"}
SKIP_TOP = {"build", "out", "Testing", "docs"}
ROW = re.compile(r"^\|\s*`([A-Za-z0-9_./-]+/)`\s*\|")


def named_folders(root):
    """The folders the table names, in order, without the trailing '/'."""
    path = os.path.join(root, DOC)
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        sys.exit(f"architecture_folders: cannot read {path}: {e.strerror}")
    try:
        start = lines.index(SECTION)
    except ValueError:
        sys.exit(f"architecture_folders: {DOC} has no section '{SECTION}'")
    folders = []
    for line in lines[start + 1:]:
        if line.startswith("## "):
            break
        m = ROW.match(line)
        if m:
            folders.append(m.group(1).rstrip("/"))
    if not folders:
        sys.exit(f"architecture_folders: {DOC}'s '{SECTION}' has no table of `folder/` rows")
    return folders


def repository_files(root):
    """Relative paths of the repository's files (git's view when root is a work tree)."""
    if os.path.exists(os.path.join(root, ".git")):
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], check=True, capture_output=True).stdout
        return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(root, p))]
    files = []
    for d, subdirs, names in os.walk(root):
        subdirs[:] = [s for s in subdirs if not s.startswith(".")]
        files += [os.path.relpath(os.path.join(d, n), root) for n in names]
    return files


def is_source(root, rel):
    if os.path.splitext(rel)[1] in SOURCE_EXTENSIONS:
        return True
    try:
        with open(os.path.join(root, rel), "rb") as f:
            return f.read(2) == b"#!"
    except OSError:
        return False


def source_folders(root):
    """Folders that must be named: sim/** holding sources directly, top-level ones holding any."""
    need = set()
    for rel in repository_files(root):
        parts = rel.split("/")
        if len(parts) < 2 or parts[0].startswith(".") or parts[0] in SKIP_TOP:
            continue
        if not is_source(root, rel):
            continue
        need.add(parts[0])
        if parts[0] == "sim" and len(parts) > 2:
            need.add("/".join(parts[:-1]))
    return need


def check(root):
    """Problems, one line each; empty when the table matches the tree."""
    named = named_folders(root)
    problems = [f"{DOC} names `{d}/`, which does not exist"
                for d in named if not os.path.isdir(os.path.join(root, d))]
    problems += [f"`{d}/` holds sources but {DOC}'s '{SECTION}' table does not name it"
                 for d in sorted(source_folders(root) - set(named))]
    return problems


def self_test():
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    named = named_folders(root)
    tmp = tempfile.mkdtemp(prefix="architecture_folders.")
    try:
        os.makedirs(os.path.join(tmp, "docs"))
        shutil.copy(os.path.join(root, DOC), os.path.join(tmp, DOC))
        for d in named:
            os.makedirs(os.path.join(tmp, d), exist_ok=True)
            with open(os.path.join(tmp, d, "x.h"), "w") as f:
                f.write("// a source\n")
        failures = []
        if check(tmp):
            failures.append(f"a tree matching the table failed: {check(tmp)}")
        missing = next(d for d in named if d.startswith("sim/") and d.count("/") >= 2)
        shutil.rmtree(os.path.join(tmp, missing))
        got = check(tmp)
        if not any(f"`{missing}/`, which does not exist" in p for p in got):
            failures.append(f"removing {missing}/ was not reported: {got}")
        os.makedirs(os.path.join(tmp, missing))
        os.makedirs(os.path.join(tmp, "sim/eda/unnamed_tool"))
        with open(os.path.join(tmp, "sim/eda/unnamed_tool/driver.cpp"), "w") as f:
            f.write("// a source\n")
        os.makedirs(os.path.join(tmp, "newtop/deep"))
        with open(os.path.join(tmp, "newtop/deep/run"), "w") as f:
            f.write("#!/bin/sh\n")
        got = check(tmp)
        for extra in ("sim/eda/unnamed_tool", "newtop"):
            if not any(f"`{extra}/` holds sources" in p for p in got):
                failures.append(f"the extra folder {extra}/ was not reported: {got}")
        if len(got) != 2:
            failures.append(f"expected exactly the two extra folders reported, got {got}")
    finally:
        shutil.rmtree(tmp)
    if failures:
        print("architecture_folders self-test: FAIL\n  " + "\n  ".join(failures))
        return 1
    print(f"architecture_folders self-test: pass ({len(named)} folders; a missing and two extra "
          "folders reported)")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    problems = check(root)
    for p in problems:
        print(f"architecture_folders: {p}")
    if problems:
        return 1
    print(f"architecture_folders: {len(named_folders(root))} folders named in {DOC}, all exist; "
          "every folder holding sources is named")
    return 0


if __name__ == "__main__":
    sys.exit(main())
