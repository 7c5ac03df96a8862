#!/usr/bin/env python3
"""docs/ and --help agree (brief item 6: "--help matches").

1. Every --help block quoted in docs/*.md equals what the tool prints. A block is a fenced code block with
   a line "Usage: rk-<tool> [<sub>] ..."; the tool is run with that subcommand and --help, and the block,
   from its Usage line on, must equal the output from its Usage line on (trailing spaces ignored).
2. Every option that a tool or subcommand lists in its --help is named in the tool's pages
   (docs/<tool>*.md; rk-nightly, rk-slurm and rk-report are in docs/rk-run.md), by its long or its short form.
Usage: help_matches_docs.py DOCS_DIR BIN_DIR
"""
import functools
import os
import re
import subprocess
import sys


def blocks(path):
    """Yields (line number, lines) of each fenced code block of a Markdown file."""
    inside, start, cur = False, 0, []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if line.startswith("```"):
                if inside:
                    yield start, cur
                inside, start, cur = not inside, n + 1, []
            elif inside:
                cur.append(line.rstrip())


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from cli_manual import doc_pages  # noqa: E402 - a tool's pages: the man pages' SEE ALSO uses the same rule


@functools.lru_cache(maxsize=None)
def run_help(cmd):
    """(exit code, stdout) of `cmd --help` (cmd a tuple): each tool and subcommand is run once, though both
    checks below read it (a sanitized tool takes a tenth of a second to start)."""
    out = subprocess.run(list(cmd) + ["--help"], capture_output=True, text=True, check=False)
    return out.returncode, out.stdout


def help_options(cmd):
    """(options as (short or None, long), subcommands) listed by `cmd --help` (CLI11 or argparse)."""
    out = run_help(tuple(cmd))[1]
    opts = set()
    for m in re.finditer(r"^\s+(?:(-\w)(?: \w+)?,\s*)?(--[a-z][a-z0-9-]*)", out, re.M):
        opts.add((m.group(1), m.group(2)))
    subs = []
    if "Subcommands:" in out:
        subs = re.findall(r"^  ([a-z][a-z0-9-]*)\s", out.split("Subcommands:")[1], re.M)
    return opts, subs


def undocumented_options(docs, bindir):
    missing = 0
    tools = sorted(n for n in os.listdir(bindir)
                   if n.startswith("rk-") and "." not in n and os.access(os.path.join(bindir, n), os.X_OK)
                   and os.path.isfile(os.path.join(bindir, n)))
    for tool in tools:
        pages = [os.path.join(docs, n) for n in doc_pages(tool, docs)]
        if not pages:
            print("%s: no page in %s" % (tool, docs))
            missing += 1
            continue
        text = "".join(open(p, encoding="utf-8").read() for p in pages)
        opts, subs = help_options([os.path.join(bindir, tool)])
        todo = [("", o) for o in opts]
        for sub in subs:
            todo += [(sub, o) for o in help_options([os.path.join(bindir, tool), sub])[0]]
        for sub, (short, long_) in sorted(todo, key=lambda x: (x[0], x[1][1])):
            if long_ in ("--help", "--version") or long_ in text:
                continue
            if short and re.search(r"(^|[\s`\[(])" + re.escape(short) + r"($|[\s`\],=)])", text, re.M):
                continue
            print("%s: '%s %s %s' is not named in %s" % (tool, tool, sub, long_, ", ".join(pages)))
            missing += 1
    print("%d tool(s) checked for undocumented options, %d missing" % (len(tools), missing))
    return missing


def main():
    docs, bindir = sys.argv[1], sys.argv[2]
    checked, bad = 0, 0
    for name in sorted(os.listdir(docs)):
        if not name.endswith(".md"):
            continue
        path = os.path.join(docs, name)
        for start, lines in blocks(path):
            at = next((i for i, l in enumerate(lines) if re.match(r"Usage: rk-\w+", l)), None)
            if at is None:
                continue
            words = lines[at].split()
            cmd = [os.path.join(bindir, words[1])]
            if len(words) > 2 and re.fullmatch(r"[a-z][a-z0-9-]*", words[2]):
                cmd.append(words[2])
            code, stdout = run_help(tuple(cmd))
            got = [l.rstrip() for l in stdout.splitlines()]
            g = next((i for i, l in enumerate(got) if l.startswith("Usage: ")), None)
            want = lines[at:]
            while want and not want[-1]:
                want.pop()
            have = got[g:] if g is not None else []
            while have and not have[-1]:
                have.pop()
            checked += 1
            if code != 0 or have != want:
                bad += 1
                diff = next((i for i in range(max(len(want), len(have)))
                             if i >= len(want) or i >= len(have) or want[i] != have[i]), 0)
                print("%s:%d: --help of '%s' differs from the tool's (first at block line %d):\n  doc:  %s\n  tool: %s"
                      % (path, start + at + diff, " ".join(words[1:3]), at + diff + 1,
                         want[diff] if diff < len(want) else "<end>", have[diff] if diff < len(have) else "<end>"))
    print("%d --help block(s) checked, %d differ" % (checked, bad))
    bad += undocumented_options(docs, bindir)
    if checked == 0:
        print("no --help block found in %s" % docs)
        return 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
