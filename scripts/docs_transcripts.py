#!/usr/bin/env python3
"""Keeps the command transcripts and pictures in the docs true.

A transcript is an indented code block (4 spaces) in README.md or docs/*.md
whose lines starting with "$ " are commands and whose other lines are what
the command prints on stdout, e.g.

    $ build/bin/deltamesh -pA examples/plate.poly
    Constrained Delaunay triangulation: 20 input vertices, 21 segments, 2 holes -> 24 triangles
      wrote examples/plate.1.node

Each block runs in a fresh temporary directory holding a copy of examples/;
"deltamesh" and "deltamesh-gen" (with or without build/bin/) are the built
tools. The commands of a block run in order.

  --check     (the ctest test docs_transcripts) fails, showing the difference,
              when a command prints anything else or fails
  --update    (make docs) rewrites the expected lines with what the tools print
  --pictures  with --update: every NAME.svg a block writes for which the
              docs show img/NAME.png is rendered to docs/img/NAME.png
              (rsvg-convert -w 420)
"""
import argparse
import difflib
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INDENT = "    "


def blocks(lines):
    """(start, end) line ranges of indented code blocks that begin with '$ '."""
    i = 0
    while i < len(lines):
        if lines[i].startswith(INDENT + "$ ") and (i == 0 or not lines[i - 1].startswith(INDENT)):
            j = i
            while j < len(lines) and lines[j].startswith(INDENT):
                j += 1
            yield i, j
            i = j
        else:
            i += 1


def tool(word, cli, gen):
    name = os.path.basename(word)
    if name == "deltamesh":
        return cli
    if name == "deltamesh-gen":
        return gen
    return None


def run_block(block, cli, gen, workdir):
    """Runs the block's commands; returns the transcript as printed (list of
    lines, commands included) and an error text or None."""
    shutil.copytree(os.path.join(ROOT, "examples"), os.path.join(workdir, "examples"))
    out = []
    for line in block:
        text = line[len(INDENT):]
        if not text.startswith("$ "):
            continue
        out.append(line.rstrip())
        argv = shlex.split(text[2:])
        exe = tool(argv[0], cli, gen)
        if exe is None:
            return out, "unknown program %r (deltamesh or deltamesh-gen)" % argv[0]
        p = subprocess.run([exe] + argv[1:], cwd=workdir, capture_output=True, text=True, timeout=300)
        if p.returncode != 0:
            return out, "%s exited %d: %s" % (text[2:], p.returncode, p.stderr.strip())
        out.extend(INDENT + l.rstrip() for l in p.stdout.splitlines())
    return out, None


def pictures(block, workdir, doc_text):
    """Renders NAME.svg written by the block to docs/img/NAME.png when the docs show it."""
    made = []
    for line in block:
        for name in re.findall(r"(?:--output|--svg)\s+(\S+)\.svg", line):
            png = os.path.join(ROOT, "docs", "img", os.path.basename(name) + ".png")
            if "img/%s.png" % os.path.basename(name) not in doc_text:
                continue
            subprocess.run(["rsvg-convert", "-w", "420", "-o", png, os.path.join(workdir, name + ".svg")], check=True)
            made.append(os.path.relpath(png, ROOT))
    return made


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true")
    mode.add_argument("--update", action="store_true")
    ap.add_argument("--pictures", action="store_true")
    ap.add_argument("--cli", required=True)
    ap.add_argument("--gen", required=True)
    ap.add_argument("docs", nargs="*")
    a = ap.parse_args()
    cli, gen = os.path.abspath(a.cli), os.path.abspath(a.gen)
    docs = a.docs or [os.path.join(ROOT, "README.md")] + sorted(
        os.path.join(ROOT, "docs", f) for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md"))
    failures = 0
    checked = 0
    for doc in docs:
        with open(doc) as f:
            text = f.read()
        lines = text.split("\n")
        new_lines = list(lines)
        shift = 0
        for start, end in blocks(lines):
            block = lines[start:end]
            with tempfile.TemporaryDirectory(prefix="deltamesh-docs-") as workdir:
                got, error = run_block(block, cli, gen, workdir)
                checked += 1
                where = "%s:%d" % (os.path.relpath(doc, ROOT), start + 1)
                if error:
                    print("%s: %s" % (where, error))
                    failures += 1
                    continue
                if a.update and a.pictures:
                    for png in pictures(block, workdir, text):
                        print("%s: rendered %s" % (where, png))
            expected = [l.rstrip() for l in block]
            if got != expected:
                if a.check:
                    failures += 1
                    print("%s: the docs quote output the tools no longer print:" % where)
                    sys.stdout.writelines(difflib.unified_diff([l + "\n" for l in expected], [l + "\n" for l in got],
                                                               "docs", "tools"))
                else:
                    new_lines[start + shift:end + shift] = got
                    shift += len(got) - len(block)
                    print("%s: updated" % where)
        if a.update and new_lines != lines:
            with open(doc, "w") as f:
                f.write("\n".join(new_lines))
    print("docs_transcripts: %d blocks, %d failed" % (checked, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
