#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks every relative link of README.md and docs/*.md.

A link to a file must name one that exists; a link with a #fragment must
name a heading of its target (or of the same page) under GitHub's rule:
the heading's text lowercased, punctuation removed, spaces made hyphens,
and -1, -2, ... after repeats. Links to other sites are not fetched.

Usage: check_links.py SOURCE_DIR
Exit status: 0 every link resolves, 1 one does not, 2 usage.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def strip_code(text):
    """The text with fenced blocks and inline code blanked, lines kept."""
    out, fence = [], None
    for line in text.split("\n"):
        m = re.match(r"^\s*(`{3,})", line)
        if fence is None and m:
            fence = m.group(1)
            out.append("")
        elif fence is not None:
            if line.strip().startswith(fence) and line.strip().strip("`") == "":
                fence = None
            out.append("")
        else:
            out.append(re.sub(r"`[^`\n]*`", lambda c: " " * len(c.group(0)), line))
    return "\n".join(out)


def slug(heading):
    heading = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text only
    heading = heading.strip().lower()
    heading = re.sub(r"[^\w\- ]", "", heading)
    return heading.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, found = {}, set()
        fence = None
        with open(path, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"^\s*(`{3,})", line)
                if m and fence is None:
                    fence = m.group(1)
                    continue
                if fence is not None:
                    if line.strip().startswith(fence) and line.strip().strip("`") == "":
                        fence = None
                    continue
                found.update(re.findall(r"<a\s+(?:id|name)=\"([^\"]+)\"", line))
                h = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
                if h:
                    a = slug(h.group(1))
                    n = seen.get(a, 0)
                    seen[a] = n + 1
                    found.add(a if n == 0 else f"{a}-{n}")
        cache[path] = found
    return cache[path]


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = os.path.abspath(sys.argv[1])
    docs = os.path.join(root, "docs")
    pages = [os.path.join(root, "README.md")]
    pages += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    bad = checked = 0
    for page in pages:
        rel = os.path.relpath(page, root)
        with open(page, encoding="utf-8") as f:
            text = strip_code(f.read())
        for m in LINK.finditer(text):
            target = m.group(2)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                continue  # http:, https:, mailto:: another site
            checked += 1
            line = text.count("\n", 0, m.start()) + 1
            path, _, fragment = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            problem = None
            if not os.path.exists(dest):
                problem = f"no such file: {path}"
            elif fragment:
                if not dest.endswith(".md") or os.path.isdir(dest):
                    problem = f"#{fragment} on a page that is not Markdown"
                elif fragment not in anchors(dest):
                    problem = f"no heading #{fragment} in {os.path.relpath(dest, root)}"
            if problem:
                bad += 1
                print(f"{rel}:{line}: error: broken link ({target}): {problem}")
    print(f"check_links: {checked} relative links in {len(pages)} pages, {bad} broken")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
