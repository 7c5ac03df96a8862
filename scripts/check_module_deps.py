#!/usr/bin/env python3
"""Check that library modules include only the modules docs/architecture.md allows.

docs/architecture.md holds the module graph as a table whose rows are

    | `module` | `dep1`, `dep2`, ... | why |

(the section headed "Module graph"). Every #include "<other>/<file>.h" in lib/<module>/ (headers and
sources) must name the module itself or one of its allowed modules. A module missing from the table,
or a table row for a folder that does not exist, is an error too: the page must stay true.

The graph is written a second time in each lib/<module>/CMakeLists.txt (rk_add_module's PUBLIC and PRIVATE
rangekit::<module> lists): those must be exactly the table's row, so the link order and the page agree.
Third-party libraries with one owner (THIRD_PARTY_OWNER) may be included and linked by that module only.

  check_module_deps.py [REPO]            exit 1 and one line per violation
  check_module_deps.py [REPO] --graph    print the graph found in the sources (module: used modules)
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"', re.M)
SYSTEM_INCLUDE = re.compile(r'^\s*#\s*include\s+<([A-Za-z_]+)/[^>]+>', re.M)
CMAKE_MODULE = re.compile(r"rangekit::([a-z_]+)")
CMAKE_ADD = re.compile(r"rk_add_module\(\s*([a-z_]+)(.*?)\)", re.S)
# Include folder or CMake target prefix of a third-party library → the one module that owns it.
THIRD_PARTY_OWNER = {"GeographicLib": "geo"}
ROW = re.compile(r"^\|\s*`([a-z_]+)`\s*\|([^|]*)\|")


def modules(repo):
    lib = os.path.join(repo, "lib")
    return sorted(d for d in os.listdir(lib) if os.path.isfile(os.path.join(lib, d, "CMakeLists.txt")))


def used(repo, module):
    """{used module: first 'file:line' that includes it}"""
    found = {}
    folder = os.path.join(repo, "lib", module)
    for name in sorted(os.listdir(folder)):
        if not name.endswith((".h", ".cc", ".hpp", ".cpp", ".in")):
            continue
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            text = f.read()
        for m in INCLUDE.finditer(text):
            dep = m.group(1)
            if dep != module and dep not in found:
                line = text.count("\n", 0, m.start()) + 1
                found[dep] = "lib/%s/%s:%d" % (module, name, line)
    return found


def without_cmake_comments(text):
    """CMake text with every '# ...' comment blanked (line numbers kept)."""
    return re.sub(r"#[^\n]*", "", text)


def cmake_deps(repo, module):
    """rangekit:: modules named in rk_add_module(module ...) of lib/<module>/CMakeLists.txt, or None."""
    with open(os.path.join(repo, "lib", module, "CMakeLists.txt"), encoding="utf-8") as f:
        text = without_cmake_comments(f.read())
    m = CMAKE_ADD.search(text)
    return None if m is None else set(CMAKE_MODULE.findall(m.group(2))) - {module}


def third_party_problems(repo, module):
    """Lines of lib/<module>/ that include or link a third-party library another module owns."""
    problems = []
    folder = os.path.join(repo, "lib", module)
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        cmake = name == "CMakeLists.txt"
        if cmake:
            text = without_cmake_comments(text)
        for lib, owner in THIRD_PARTY_OWNER.items():
            if owner == module:
                continue
            for m in (re.finditer(r"(%s)::" % lib, text) if cmake else SYSTEM_INCLUDE.finditer(text)):
                if m.group(1) == lib:
                    problems.append("lib/%s/%s:%d: %s belongs to module '%s' (scripts/check_module_deps.py)"
                                    % (module, name, text.count("\n", 0, m.start()) + 1, lib, owner))
    return problems


def allowed(repo):
    path = os.path.join(repo, "docs", "architecture.md")
    table, inside = {}, False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                inside = line.lstrip("#").strip().lower().startswith("module graph")
                continue
            m = ROW.match(line) if inside else None
            if m:
                deps = [d.strip(" `") for d in m.group(2).split(",")]
                table[m.group(1)] = {d for d in deps if d and d != "—" and d != "-"}
    return table


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    repo = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    mods = modules(repo)
    if "--graph" in sys.argv:
        for m in mods:
            print("%s: %s" % (m, ", ".join(sorted(used(repo, m))) or "-"))
        return 0
    table = allowed(repo)
    problems = []
    if not table:
        problems.append("docs/architecture.md: no 'Module graph' table")
    for m in mods:
        if m not in table:
            problems.append("docs/architecture.md: module '%s' (lib/%s) is not in the module graph" % (m, m))
            continue
        for dep, where in sorted(used(repo, m).items()):
            if dep not in table[m]:
                problems.append("%s: module '%s' includes '%s/...', which docs/architecture.md does not allow"
                                % (where, m, dep))
        linked = cmake_deps(repo, m)
        if linked is None:
            problems.append("lib/%s/CMakeLists.txt: no rk_add_module(%s ...)" % (m, m))
        elif linked != table[m]:
            extra, missing = sorted(linked - table[m]), sorted(table[m] - linked)
            problems.append("lib/%s/CMakeLists.txt: rk_add_module lists %s; docs/architecture.md's row says %s%s%s"
                            % (m, ", ".join(sorted(linked)) or "no module", ", ".join(sorted(table[m])) or "none",
                               " (not in the row: %s)" % ", ".join(extra) if extra else "",
                               " (not linked: %s)" % ", ".join(missing) if missing else ""))
        problems += third_party_problems(repo, m)
    for m in sorted(set(table) - set(mods)):
        problems.append("docs/architecture.md: module '%s' has no folder lib/%s" % (m, m))
    for p in problems:
        print(p)
    print("%d module(s), %d problem(s)" % (len(mods), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
