#!/usr/bin/env python3
"""Lists the C++ functions longer than a limit (issue 16: no function over ~120 lines without a reason).

    scripts/long_functions.py [--max-lines 120] [--check] [DIR_OR_FILE ...]   (default: lib apps)

A function's length is counted from the first line of its declaration to its closing brace, both
included. Lambdas and local classes count towards the function that holds them; member functions
defined in a class body are functions of their own. A function may stay long when the comment block
right above it says why, in a line `// Long function: <the reason>` (docs/architecture.md, "A long
function"); template lines between the comment and the function are allowed. The scan is a plain brace matcher over
the source with comments, string and character literals and preprocessor lines blanked out (no
compiler needed, so its answer does not depend on the build); it prints one line per long function,
longest first, and the longest function of all.

--check: exit 1 when a long function has no reason written above it, naming each such function on stderr.
"""
import argparse
import os
import re
import sys

REASON_MARK = "Long function:"
SOURCE_EXT = (".cc", ".cpp", ".h", ".hpp")
CONTROL = {"if", "for", "while", "switch", "catch", "do", "else", "try", "return", "sizeof", "decltype",
           "alignof", "static_assert", "noexcept", "requires"}
SCOPE_WORDS = re.compile(r"^(?:template\s*<.*>\s*)?(?:class|struct|union|enum|namespace|extern)\b")


def blank(text):
    """The text with comments, literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            # Preprocessor line, with its continuations.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("  \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "\n":
            out.append(c)
            line_start = True
            i += 1
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        m = re.match(r'(?:u8|u|U|L)?R"([^ ()\\\t\n]{0,16})\(', text[i:i + 24])
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            close = ")" + m.group(1) + '"'
            end = text.find(close, i + m.end())
            end = n if end < 0 else end + len(close)
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        if c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
            continue
        out.append(c)
        i += 1
    return "".join(out)


def function_name(header):
    """The name of the function a block header declares, or None if the block is not a function body."""
    h = " ".join(header.split())
    if not h or SCOPE_WORDS.match(h):
        return None
    depth = 0
    paren = -1
    for k, ch in enumerate(h):
        if ch == "(":
            if depth == 0 and paren < 0:
                paren = k
            depth += 1
        elif ch == ")":
            depth -= 1
        elif ch == "=" and depth == 0 and paren < 0 and not h.startswith("operator", max(0, k - 8)):
            return None  # an initialiser or a lambda assigned to a variable
    if paren < 0:
        return None
    before = h[:paren].rstrip()
    if before.endswith("]") or before.endswith("operator"):
        if before.endswith("]"):
            return None  # a lambda
    m = re.search(r"(operator\s*\S+|~?[A-Za-z_][\w:]*(?:<[^()]*>)?(?:::~?[A-Za-z_]\w*)?)$", before)
    if not m:
        return None
    name = m.group(1)
    if name.split("::")[-1] in CONTROL or name in CONTROL:
        return None
    return name


def scan(path):
    """(name, first line, last line) of every function body in the file."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        text = blank(fh.read())
    found = []
    stack = []  # kinds: "scope" (namespace, class, extern), "func", "other"
    header_start = 0
    init_depth = 0  # brace-initialisers inside a constructor's member-initialiser list
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "{":
            in_scope = all(k == "scope" for k, _, _ in stack)
            header = text[header_start:i]
            hs = " ".join(header.split())
            if in_scope and re.search(r"\)\s*(?:const\s*)?(?:noexcept\s*)?:\s", hs) and re.search(r"[\w>]\s*$", hs) \
                    and function_name(hs) is not None:
                # `Ctor(...) : member_{value}`: a brace-initialiser, the body comes later.
                depth = 1
                j = i + 1
                while j < n and depth:
                    depth += {"{": 1, "}": -1}.get(text[j], 0)
                    j += 1
                i = j
                continue
            if in_scope:
                name = function_name(hs)
                if name is not None:
                    first = text.count("\n", 0, header_start + len(header) - len(header.lstrip())) + 1
                    stack.append(("func", name, first))
                elif SCOPE_WORDS.match(hs) and "=" not in hs.split("{")[0]:
                    stack.append(("scope", None, 0))
                else:
                    stack.append(("other", None, 0))
            else:
                stack.append(("other", None, 0))
            header_start = i + 1
        elif c == "}":
            if stack:
                kind, name, first = stack.pop()
                if kind == "func":
                    found.append((name, first, text.count("\n", 0, i) + 1))
            header_start = i + 1
        elif c == ";":
            header_start = i + 1
        i += 1
    return found


def reason_above(lines, first):
    """True when the comment block right above line `first` (1-based) holds REASON_MARK."""
    k = first - 2
    while k >= 0 and lines[k].strip().startswith("template"):
        k -= 1
    while k >= 0 and lines[k].strip().startswith("//"):
        if REASON_MARK in lines[k]:
            return True
        k -= 1
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 allow_abbrev=False)
    ap.add_argument("paths", nargs="*", default=["lib", "apps"])
    ap.add_argument("--max-lines", type=int, default=120)
    ap.add_argument("--check", action="store_true", help="exit 1 if a long function has no reason above it")
    args = ap.parse_args()
    files = []
    for p in args.paths:
        if os.path.isfile(p):
            files.append(p)
            continue
        for root, dirs, names in os.walk(p):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            files.extend(os.path.join(root, f) for f in sorted(names) if f.endswith(SOURCE_EXT))
    rows = []
    for path in files:
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.read().split("\n")
        for name, first, last in scan(path):
            rows.append((last - first + 1, path, first, name, reason_above(lines, first)))
    rows.sort(key=lambda r: (-r[0], r[1], r[2]))
    missing = 0
    for length, path, first, name, why in rows:
        if length <= args.max_lines:
            break
        print(f"{path}:{first}: {name}: {length} lines{'' if why else '  (no reason written above it)'}")
        missing += 0 if why else 1
    if rows:
        length, path, first, name, _ = rows[0]
        print(f"longest: {path}:{first}: {name}: {length} lines ({len(rows)} functions scanned)")
    if args.check and missing:
        for length, path, first, name, why in rows:
            if length <= args.max_lines:
                break
            if not why:
                print(f"{path}:{first}: {name}: {length} lines, no '// {REASON_MARK} <reason>' above it", file=sys.stderr)
        print(f"{missing} function(s) over {args.max_lines} lines without a '{REASON_MARK}' comment above them",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
