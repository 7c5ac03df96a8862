#!/usr/bin/env python3
"""Man pages and bash completion of the rk tools, made from their own --help (one owner: the tool).

  cli_manual.py man TOOL OUT.1            man page of TOOL (an rk-* executable or Python tool) by help2man,
                                          with one section per subcommand (its --help)
  cli_manual.py completion TOOL OUT       bash completion file of TOOL: options of the tool and of each
                                          subcommand, choice values, file names after path options
  cli_manual.py completion-rk OUT         bash completion of the `rk` dispatcher (tool names, then the
                                          tool's own completion)

CLI11's help is parsed: an "Options:" block (two-space indent, names separated by commas, then the
value type: TEXT, FLOAT, INT, UINT, TEXT:{a,b}=default, ...), a "Subcommands:" block (name, then its
description), a "Positionals:" block. So is argparse's (the Python tools rk-plot, rk-report, rk-nightly,
rk-slurm): "usage: ..." first, an "options:" block ("-o OUT, --output OUT", "--kind {a,b}"; the description
on the same line or indented below), "positional arguments:" (a "{a,b}" line then the subcommands indented
by four). Run by the build (apps/CMakeLists.txt) after each tool is linked; installed by
`cmake --install` to share/man/man1 and share/bash-completion/completions.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

OPTION = re.compile(r"^  (-[^\s]+)(?: ([A-Z][A-Z0-9_]*(?::\{[^}]*\})?(?:=\S*)?(?: \[[^\]]*\])?(?: x \d+)?))?")
SUB = re.compile(r"^  ([a-z][a-z0-9_-]*)\s{2,}")
# Value types that name a path (complete file names after them).
PATH_WORDS = ("path", "file", "csv", "json", "dir", "video", "folder", "png", "pattern", "images", "trial", "out")
DOCS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs")
# Tools documented in another tool's page rather than in docs/<tool>.md.
DOCUMENTED_IN = {"rk-nightly": ["rk-run"], "rk-slurm": ["rk-run"], "rk-report": ["rk-run"]}


def doc_pages(tool, docs=DOCS):
    """The file names of a tool's pages in docs/: <tool>.md and <tool>-<part>.md (rk-attitude-oi.md,
    rk-smooth-singer-resample.md), or those of the tool that documents it (DOCUMENTED_IN). The one rule for
    the man pages' SEE ALSO and for tests/cli/help_matches_docs.py."""
    stems = DOCUMENTED_IN.get(tool, [tool])
    return [n for n in sorted(os.listdir(docs))
            if n.endswith(".md") and any(n == s + ".md" or n.startswith(s + "-") for s in stems)]


def help_text(argv):
    out = subprocess.run(argv + ["--help"], capture_output=True, text=True, timeout=60)
    return out.stdout


def parse(text):
    """(options, subcommands, positionals): options [(names, type or None, description)], subcommands
    [(name, desc)], positionals [name]."""
    if text.startswith("usage:"):
        return parse_argparse(text)
    options, subs, pos, block = [], [], [], None
    for line in text.splitlines():
        if line.startswith("Options:"):
            block = "opt"
            continue
        if line.startswith("Subcommands:"):
            block = "sub"
            continue
        if line.startswith("Positionals:"):
            block = "pos"
            continue
        if block == "pos" and re.match(r"^  [a-z]", line):
            pos.append(line.split()[0])
        if block == "opt":
            m = OPTION.match(line)
            if m:
                names = m.group(1).split(",")
                rest = line[m.end():].strip()
                options.append([names, m.group(2), rest])
            elif options and line.startswith("    "):
                options[-1][2] = (options[-1][2] + " " + line.strip()).strip()
        elif block == "sub":
            m = SUB.match(line)
            if m:
                subs.append((m.group(1), line[m.end():].strip()))
    return options, subs, pos


ARGPARSE_OPTION = re.compile(r"^  (-\S+(?: [^\s,]+)?(?:, -\S+(?: [^\s,]+)?)*)(?:\s{2,}(.*))?$")


def parse_argparse(text):
    """parse() for argparse's --help: METAVARs become the value type ("TEXT", or "TEXT:{a,b}" for choices),
    so that the rest of this file treats both alike."""
    options, subs, pos, block = [], [], [], None
    for line in text.splitlines():
        if line in ("options:", "optional arguments:"):
            block = "opt"
            continue
        if line == "positional arguments:":
            block = "pos"
            continue
        if not line.strip() or not line.startswith(" "):
            block = None  # a blank line ends argparse's blocks (the epilog follows)
            continue
        if block == "opt":
            m = ARGPARSE_OPTION.match(line)
            if m:
                names, type_ = [], None
                for part in m.group(1).split(", "):
                    name, _, metavar = part.partition(" ")
                    names.append(name)
                    if metavar:
                        type_ = "TEXT:" + metavar if metavar.startswith("{") else "TEXT"
                options.append([names, type_, (m.group(2) or "").strip()])
            elif options and line.startswith("      "):
                options[-1][2] = (options[-1][2] + " " + line.strip()).strip()
        elif block == "pos":
            if re.match(r"^    [a-z]", line):
                subs.append((line.split()[0], line.strip()[len(line.split()[0]):].strip()))
            elif re.match(r"^  [a-z]", line):
                pos.append(line.split()[0])
    return options, subs, pos


def description(text):
    """The tool's one-line summary: CLI11 prints its description first; argparse prints the usage first,
    then a blank line and the description. A leading "rk-<tool>: " is dropped."""
    lines = text.splitlines()
    if text.startswith("usage:"):
        start = lines.index("") + 1 if "" in lines else 0
        para = []
        for line in lines[start:]:
            if not line.strip():
                break
            para.append(line.strip())
        first = " ".join(para)
    else:
        first = lines[0] if lines else ""
    first = re.sub(r"^rk-[a-z]+: ", "", first)
    return re.split(r"(?<=[.:])\s", first)[0].rstrip(".:")


def choices(type_):
    m = re.search(r":\{([^}]*)\}", type_ or "")
    return m.group(1).split(",") if m else []


def takes_path(names, type_, desc):
    if not type_ or not type_.startswith("TEXT") or choices(type_):
        return False
    if re.search(r"default:? [0-9.]+\b", desc):
        return False  # a number (argparse types every value TEXT here): "--time ... (default 60 minutes)"
    words = " ".join(names).lower() + " " + desc.lower()
    return any(w in words for w in PATH_WORDS) or names[-1] in ("-o", "--output", "-i", "--input")


def cmd_man(tool, out):
    name = os.path.basename(tool)
    text = help_text([tool])
    _, subs, _ = parse(text)
    summary = description(text) or name
    include = "[NAME]\n%s \\- %s\n" % (name, summary)
    if subs:
        include += "[SUBCOMMANDS]\n"
        for sub, _ in subs:
            include += ".SS %s %s\n.nf\n%s\n.fi\n" % (name, sub, help_text([tool, sub]).replace("\\", "\\\\"))
    # Only pages that exist (issue 27: rk-nightly, rk-report, rk-slurm and rk-attitude named docs/<tool>.md).
    pages = ", ".join("docs/" + p for p in doc_pages(name))
    include += ("[SEE ALSO]\nrk(1)%s; the interface contract, SPEC.md in the project's shared documents.\n"
                % ("; the tool's pages in the rangekit docs: " + pages if pages else ""))
    with tempfile.NamedTemporaryFile("w", suffix=".h2m", delete=False) as f:
        f.write(include)
        inc = f.name
    try:
        tmp = out + ".tmp"
        subprocess.run(["help2man", "--no-info", "--no-discard-stderr", "--section=1",
                        "--source=rangekit", "--manual=rangekit", "--include=" + inc, "--output=" + tmp, tool],
                       check=True, timeout=120)
        os.replace(tmp, out)
    finally:
        os.unlink(inc)


def function_name(name):
    return "_" + re.sub(r"[^A-Za-z0-9]", "_", name)


def completion_body(tool):
    """Bash case arms for the tool: per subcommand (and "" for the top level) its words, path options,
    choice options."""
    name = os.path.basename(tool)
    top_opts, subs, pos = parse(help_text([tool]))
    levels = [("", top_opts, [s for s, _ in subs])]
    # Common options (--report, --quiet, ...) are accepted after a subcommand too (CLI11 fallthrough).
    common = [o for o in top_opts if o[0][-1] not in ("--help", "--version")]
    for sub, _ in subs:
        opts, _, _ = parse(help_text([tool, sub]))
        own = {n for o in opts for n in o[0]}
        levels.append((sub, opts + [o for o in common if not own.intersection(o[0])], []))
    words_arms, prev_arms = [], []
    for sub, opts, subnames in levels:
        words = [n for o in opts for n in o[0]] + subnames
        words_arms.append("    %s) words=%s ;;" % (shlex.quote(sub) if sub else '""', shlex.quote(" ".join(words))))
        for names, type_, desc in opts:
            pattern = "|".join(names)
            key = (sub or "_top_") + ":" + pattern
            if choices(type_):
                prev_arms.append((key, "COMPREPLY=($(compgen -W %s -- \"$cur\")); return" %
                                  shlex.quote(" ".join(choices(type_)))))
            elif takes_path(names, type_, desc):
                prev_arms.append((key, "COMPREPLY=($(compgen -f -- \"$cur\")); return"))
            elif type_:
                prev_arms.append((key, "return"))  # a number or free text: nothing to offer
    return name, [s for s, _ in subs], words_arms, prev_arms, bool(pos)


def cmd_completion(tool, out):
    name, subs, words_arms, prev_arms, has_pos = completion_body(tool)
    fn = function_name(name)
    lines = ["# bash completion for %s (generated from its --help by scripts/cli_manual.py)" % name,
             "%s() {" % fn,
             '  local cur="${COMP_WORDS[COMP_CWORD]}" prev="${COMP_WORDS[COMP_CWORD-1]}" sub="" words i',
             "  for ((i = 1; i < COMP_CWORD; i++)); do",
             '    case "${COMP_WORDS[i]}" in']
    if subs:
        lines.append('      %s) sub="${COMP_WORDS[i]}"; break ;;' % "|".join(subs))
    lines += ["      *) ;;", "    esac", "  done",
              '  case "${sub:-_top_}:$prev" in']
    for key, action in prev_arms:
        level, pattern = key.split(":", 1)
        lines.append("    %s) %s ;;" % ("|".join(level + ":" + p for p in pattern.split("|")), action))
    # A word that is not an option: a subcommand name while none is chosen; else a file name when the tool
    # (or subcommand) takes one as a positional argument (rk-run TRIAL, rk-report OUT_DIR); else options.
    words_when = '"$cur" == -* || -z "$sub"' if subs else ('"$cur" == -*' if has_pos else "1 == 1")
    lines += ["    *) ;;", "  esac", '  case "$sub" in'] + words_arms + ["  esac",
              "  if [[ %s ]]; then" % words_when,
              '    COMPREPLY=($(compgen -W "$words" -- "$cur"))',
              "  else",
              '    COMPREPLY=($(compgen -f -- "$cur"))',
              "  fi",
              "}",
              "complete -F %s %s" % (fn, name), ""]
    write(out, "\n".join(lines))


def cmd_completion_rk(out):
    text = """# bash completion for rk, the dispatcher (generated by scripts/cli_manual.py): the tool names, then
# the tool's own completion (rk-<tool>'s file, loaded on demand like bash-completion does).
_rk() {
  local cur="${COMP_WORDS[COMP_CWORD]}"
  if ((COMP_CWORD == 1)); then
    local tools
    tools=$(compgen -c rk- | sed 's/^rk-//' | sort -u)
    COMPREPLY=($(compgen -W "help --version $tools" -- "$cur"))
    return
  fi
  local tool="rk-${COMP_WORDS[1]}"
  [[ "${COMP_WORDS[1]}" == help ]] && { COMPREPLY=($(compgen -W "$(compgen -c rk- | sed 's/^rk-//')" -- "$cur")); return; }
  local fn="_${tool//[^A-Za-z0-9]/_}"
  if ! declare -F "$fn" >/dev/null; then
    local here
    here=$(dirname "${BASH_SOURCE[0]}")
    if [[ -r "$here/$tool" ]]; then source "$here/$tool"
    elif declare -F _completion_loader >/dev/null; then _completion_loader "$tool"; fi
  fi
  declare -F "$fn" >/dev/null || return
  COMP_WORDS=("$tool" "${COMP_WORDS[@]:2}")
  COMP_CWORD=$((COMP_CWORD - 1))
  "$fn"
}
complete -F _rk rk
"""
    write(out, text)


def write(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "man":
        cmd_man(os.path.abspath(args[1]), args[2])
    elif len(args) == 3 and args[0] == "completion":
        cmd_completion(os.path.abspath(args[1]), args[2])
    elif len(args) == 2 and args[0] == "completion-rk":
        cmd_completion_rk(args[1])
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
