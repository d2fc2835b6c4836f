#!/usr/bin/env python3
"""Checks the repository's own pointers, so that no document points at a file or section that
is not there:

1. every relative link [text](target) in a tracked Markdown file: the file exists, and a
   #anchor names a heading of the target page (GitHub's rule: lower case; letters, marks,
   numbers, '_', '-' and spaces kept, spaces become '-'; a repeated heading gets -1, -2, ...);
2. every repository path named in a comment or document (bench/..., docs/..., kernels/...,
   results/..., scenes/..., scripts/..., solver/..., tests/... ending in a source, scene,
   data or document suffix): the file exists (names with a wildcard or a placeholder such as
   `{2,3}`, `*`, `<name>`, `NNNNN` are skipped);
3. no file points outside the repository: not to the workplace's shared reference folder or
   its benchmark notes, nor to /work/ (docs/references.md holds the setups and published values).

Usage: python3 scripts/check_links.py [ROOT]   (exit 1 and one line per problem if any)
"""
import os
import re
import subprocess
import sys
import unicodedata

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
TEXT_SUFFIXES = (".md", ".cpp", ".hpp", ".py", ".sh", ".toml", ".txt")
PATH_RE = re.compile(r"(?<![\w./-])((?:bench|docs|kernels|results|scenes|scripts|solver|tests|core)/[\w./+-]*\.(?:md|cpp|hpp|py|sh|toml|csv|png|json|txt))(?![\w])")
LINK_RE = re.compile(r"(?<!\!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
OUTSIDE = ("BENCHMARKS" + ".md", "shared" + "/reference", "/work/")


def files():
    """The repository's files: git's tracked and untracked-but-not-ignored ones, or (outside a
    git work tree) every file but build directories and dot-directories."""
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                             capture_output=True, text=True, check=True).stdout.split()
        return sorted(set(out))
    except (OSError, subprocess.CalledProcessError):
        found = []
        for d, dirs, names in os.walk(ROOT):
            dirs[:] = [x for x in dirs if not x.startswith((".", "build", "out"))]
            found += [os.path.relpath(os.path.join(d, n), ROOT) for n in names]
        return sorted(found)


def slug(heading):
    h = re.sub(r"`|\*\*|\*|\[|\]\([^)]*\)", "", heading.strip()).lower()
    kept = "".join(c for c in h if c in "- " or unicodedata.category(c)[0] in "LMN" or unicodedata.category(c) == "Pc")
    return kept.replace(" ", "-")


_anchor_cache = {}


def anchors(path):
    if path not in _anchor_cache:
        seen, out, fence = {}, set(), False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("```"):
                    fence = not fence
                m = None if fence else re.match(r"#{1,6} (.*)", line)
                if m:
                    s = slug(m.group(1))
                    n = seen.get(s, 0)
                    seen[s] = n + 1
                    out.add(s if n == 0 else f"{s}-{n}")
        _anchor_cache[path] = out
    return _anchor_cache[path]


def strip_code(text):
    """Markdown without fenced blocks and inline code (links there are examples)."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return re.sub(r"`[^`\n]*`", "", text)


def main():
    problems = []
    tracked = files()
    for rel in tracked:
        if not rel.endswith(TEXT_SUFFIXES) or rel == "scripts/check_links.py":
            continue
        path = os.path.join(ROOT, rel)
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        for bad in OUTSIDE:
            for m in re.finditer(re.escape(bad), text):
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{rel}:{line}: points outside the repository ({bad}); use docs/references.md")
        if rel.endswith(".md"):
            body = strip_code(text)
            for m in LINK_RE.finditer(body):
                target = m.group(1) or m.group(2)
                if re.match(r"[a-z]+:", target):
                    continue  # http:, https:, mailto:
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                line = body.count("\n", 0, m.start()) + 1
                if not os.path.exists(dest):
                    problems.append(f"{rel}: link to a missing file: {target}")
                elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                    problems.append(f"{rel}: link to a missing section: {target}")
        for m in PATH_RE.finditer(text):
            p = m.group(1).rstrip(".")
            if re.search(r"[*{}<>]|NNNN|_N\.|XXX", p) or p.startswith("tests/data/") and "/" in p[11:]:
                continue
            # a path relative to the file (e.g. results/ inside results/...) or to the root
            if not (os.path.exists(os.path.join(ROOT, p)) or os.path.exists(os.path.join(os.path.dirname(path), p))):
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{rel}:{line}: names a missing file: {p}")
    for p in problems:
        print(p)
    print(f"check_links: {len(problems)} problem(s) in {len(tracked)} files", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
