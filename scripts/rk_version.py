"""The version of the Python tools (rk-plot, rk-report, rk-nightly, rk-slurm), the same as the compiled
tools' (lib/io/version.h.in): the project's version and the git commit the build was made from.

The build copies this file beside the tools it copies (build/apps; lib/run/CMakeLists.txt) with CMake's
values filled in (project VERSION, cmake/GitCommit.cmake's RANGEKIT_GIT_COMMIT), and `cmake --install`
installs that copy; so an installed rk-report names the same commit as rk-run. Run straight from the
source tree (scripts/), the placeholders are still there: the version is then read from CMakeLists.txt's
project() and the commit asked of git, "unknown" if neither can tell.
"""
import os
import re
import subprocess

_VERSION = "@PROJECT_VERSION@"
_GIT_COMMIT = "@RANGEKIT_GIT_COMMIT@"


def _placeholder(value):
    return value.startswith("@") and value.endswith("@")


def _source_version():
    here = os.path.dirname(os.path.realpath(__file__))
    try:
        with open(os.path.join(here, "..", "CMakeLists.txt"), encoding="utf-8") as f:
            m = re.search(r"project\(\s*rangekit\s+VERSION\s+([0-9.]+)", f.read())
        return m.group(1) if m else "unknown"
    except OSError:
        return "unknown"


def _source_commit():
    here = os.path.dirname(os.path.realpath(__file__))
    try:
        out = subprocess.run(["git", "-C", here, "rev-parse", "--short=12", "HEAD"], capture_output=True,
                             text=True, timeout=10)
        return out.stdout.strip() if out.returncode == 0 and out.stdout.strip() else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


VERSION = _source_version() if _placeholder(_VERSION) else _VERSION
GIT_COMMIT = _source_commit() if _placeholder(_GIT_COMMIT) else _GIT_COMMIT


def version_line(tool):
    """What every tool's --version prints: "rk-<tool> (rangekit) 0.1.0 (git 0123456789ab)"."""
    return "%s (rangekit) %s (git %s)" % (tool, VERSION, GIT_COMMIT)
