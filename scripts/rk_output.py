"""Writing an output path the way every rangekit tool does (SPEC.md §2, "Writes are atomic"); the
Python twin of lib/io/file_util.cc's ResolveOutput / WriteFileAtomic, used by rk-plot, rk-nightly and
rk-slurm.

- "-" and links to this process's own descriptors (/dev/stdout, /dev/fd/N, /proc/self/fd/N): written
  to that descriptor as the shell opened it;
- a new path or a regular file: a temporary file in the same folder, flushed, then renamed over it;
- a symbolic link (chain): stays a link; its final target is replaced atomically (or written through
  when it is not a regular file);
- an existing non-regular file (/dev/null, a FIFO, a process substitution): written through in
  place, never replaced and never created, as root too."""
import os
import re
import stat
import sys
import tempfile

_OWN_FD = re.compile(r"^/(?:dev/fd|proc/(?:self|thread-self|(\d+))/fd)/(\d+)$")


def _own_descriptor(path):
    m = _OWN_FD.match(path)
    if not m or (m.group(1) is not None and int(m.group(1)) != os.getpid()):
        return -1
    return int(m.group(2))


def _follow_links(path):
    """(final path, descriptor or -1): follows a chain of links, stopping at one of our descriptors."""
    cur = path
    for _ in range(40):
        fd = _own_descriptor(cur)
        if fd >= 0:
            return cur, fd
        try:
            if not stat.S_ISLNK(os.lstat(cur).st_mode):
                return cur, -1
        except FileNotFoundError:
            return cur, -1
        target = os.readlink(cur)
        if not os.path.isabs(target):
            target = os.path.join(os.path.dirname(cur), target)
        cur = os.path.normpath(target)
    raise OSError(40, "too many levels of symbolic links", path)


def _write_all(fd, data):
    view = memoryview(data)
    while view:
        n = os.write(fd, view)
        view = view[n:]


def write_output(path, data):
    """Writes bytes or str `data` to `path` per SPEC.md §2. Raises OSError (with the path)."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    if path == "-":
        sys.stdout.flush()
        _write_all(sys.stdout.fileno(), data)
        return
    final, fd = _follow_links(path)
    if fd >= 0:
        sys.stdout.flush()
        _write_all(fd, data)
        return
    try:
        st = os.stat(final)
    except FileNotFoundError:
        st = None
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise IsADirectoryError(21, "is a folder, not a file", path)
    if st is not None and not stat.S_ISREG(st.st_mode):
        out = os.open(path, os.O_WRONLY | os.O_NOCTTY)  # no O_CREAT: never a regular file in its place
        try:
            _write_all(out, data)
        finally:
            os.close(out)
        return
    folder = os.path.dirname(os.path.abspath(final))
    tmp_fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(final) + ".", dir=folder)
    try:
        _write_all(tmp_fd, data)
        mask = os.umask(0)
        os.umask(mask)
        os.fchmod(tmp_fd, 0o666 & ~mask)
        os.fsync(tmp_fd)
        os.close(tmp_fd)
        tmp_fd = -1
        try:
            if not stat.S_ISREG(os.lstat(final).st_mode):
                raise OSError(17, "changed into something other than a regular file; not replaced", final)
        except FileNotFoundError:
            pass
        os.replace(tmp, final)
        tmp = None
    finally:
        if tmp_fd >= 0:
            os.close(tmp_fd)
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
