#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compiles every ```cpp block of README.md and docs/*.md.

A guide's C++ is only worth reading if it still builds against the headers
it names, so each block is a whole translation unit: its own #includes and
its code inside functions. Each is written to a temporary .cpp and checked
with the compiler (-fsyntax-only, warnings as errors) against every public
include directory, at most two at a time. A failure prints the guide's file
and line, then the compiler's message.

Usage: check_snippets.py SOURCE_DIR [--cxx C++] [-I DIR]... [--jobs N]
  SOURCE_DIR  the source tree: its README.md, docs/*.md and every
              `include` directory under it are used
  -I DIR      extra include directories (the build's generated headers)
Exit status: 0 every block compiled, 1 one did not, 2 usage.
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile
import time

FLAGS = ["-std=c++20", "-fsyntax-only", "-Wall", "-Wextra", "-Werror",
         # what the client SDK's consumers compile with (asio without Boost)
         "-DASIO_STANDALONE", "-DASIO_NO_DEPRECATED"]
SKIP_DIRS = {".git", "build", "node_modules"}


def markdown_files(root):
    files = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    return [f for f in files if os.path.isfile(f)]


def cpp_blocks(path):
    """(first code line's number, code) for every ```cpp fence of a file."""
    blocks, code, start, fence = [], None, 0, None
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            stripped = line.strip()
            if code is None:
                m = re.match(r"^(\s*)(`{3,})\s*([\w+-]*)", line)
                if m:
                    fence = m.group(2)
                    if m.group(3) in ("cpp", "c++"):
                        code, start = [], number + 1
                    else:
                        code, start = False, 0
                continue
            if stripped.startswith(fence) and stripped.strip("`") == "":
                if code is not False:
                    blocks.append((start, "".join(code)))
                code = None
                continue
            if code is not False:
                code.append(line)
    return blocks


def include_dirs(root):
    dirs = []
    for here, subdirs, _ in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs if d not in SKIP_DIRS)
        if os.path.basename(here) == "include" and os.path.isdir(os.path.join(here, "rewind")):
            dirs.append(here)
            subdirs[:] = []
    return dirs


def compile_one(cxx, args, tmp, rel, line, code):
    name = os.path.join(tmp, re.sub(r"[^\w]", "_", rel) + f"_{line}.cpp")
    with open(name, "w", encoding="utf-8") as f:
        f.write(code)
    run = subprocess.run([cxx, *FLAGS, *args, name], capture_output=True, text=True)
    if run.returncode == 0:
        return None
    # The compiler names the temporary file: point at the guide instead.
    def to_guide(m):
        return f"{rel}:{line + int(m.group(1)) - 1}:"
    message = re.sub(re.escape(name) + r":(\d+):", to_guide, run.stderr)
    return message.replace(name, rel).rstrip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source_dir")
    ap.add_argument("--cxx", default=os.environ.get("CXX", "c++"))
    ap.add_argument("-I", dest="includes", action="append", default=[])
    ap.add_argument("--jobs", type=int, default=2)
    opts = ap.parse_args()
    root = os.path.abspath(opts.source_dir)
    if not os.path.isfile(os.path.join(root, "README.md")):
        print(f"check_snippets: {root} has no README.md", file=sys.stderr)
        return 2
    args = [f"-I{d}" for d in include_dirs(root) + opts.includes]
    jobs = []
    for path in markdown_files(root):
        rel = os.path.relpath(path, root)
        jobs += [(rel, line, code) for line, code in cpp_blocks(path)]
    began = time.monotonic()
    failed = 0
    with tempfile.TemporaryDirectory(prefix="rewind-snippets-") as tmp, \
            concurrent.futures.ThreadPoolExecutor(max_workers=max(1, opts.jobs)) as pool:
        futures = [pool.submit(compile_one, opts.cxx, args, tmp, *job) for job in jobs]
        for (rel, line, _), future in zip(jobs, futures):
            error = future.result()
            if error is not None:
                failed += 1
                print(f"{rel}:{line}: error: this C++ block does not compile\n{error}\n")
    files = len({rel for rel, _, _ in jobs})
    print(f"check_snippets: {len(jobs)} C++ blocks in {files} files, {failed} failed "
          f"({time.monotonic() - began:.1f} s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
