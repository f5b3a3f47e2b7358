"""Small I/O helpers: atomic writes so that no output is ever half-written."""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path


@contextlib.contextmanager
def atomic_path(path, *, suffix: str | None = None):
    """Yield a temporary path next to ``path``; rename it onto ``path`` on success.

    Parameters
    ----------
    path : str or Path
        Final destination.
    suffix : str, optional
        Suffix of the temporary file (some writers pick the format from it); defaults to
        the suffix of ``path``.

    Notes
    -----
    If the body raises, the temporary file is removed and ``path`` is left untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{path.name}.", suffix=suffix if suffix is not None else path.suffix,
        dir=path.parent,
    )
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def absolute(path) -> str | None:
    """``path`` as an absolute, normalised path string (None stays None): what a run's
    ``summary.json`` stores, so that it is found from any working folder."""
    return None if path is None else os.path.abspath(os.fspath(path))


def write_text_atomic(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)


def write_matrix_csv(path, header, data, *, first: str = "%.12g", rest: str = "%.7g",
                     empty_nonfinite: bool = True) -> None:
    """A float matrix as CSV, atomically: the header row (as :mod:`csv` quotes it), then
    one row per line, the first column formatted with ``first`` (e.g. time), the others
    with ``rest``; non-finite values after the first column are left empty unless
    ``empty_nonfinite`` is False.  One format operation per row."""
    import csv
    import io

    import numpy as np

    data = np.asarray(data, dtype=float)
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(header)
    line = ",".join([first] + [rest] * (data.shape[1] - 1)) + "\n"
    finite = np.isfinite(data[:, 1:]).all(axis=1) if empty_nonfinite else \
        np.ones(len(data), dtype=bool)
    for ok, r in zip(finite.tolist(), data.tolist(), strict=True):
        if ok:
            buf.write(line % tuple(r))
        else:
            buf.write(",".join([first % r[0]] + [rest % v if np.isfinite(v) else ""
                                                 for v in r[1:]]) + "\n")
    write_text_atomic(path, buf.getvalue())


def read_numeric_rows(path, *, kind: str, columns: str):
    """Read a small numeric table (comma or whitespace separated) with line numbers.

    ``#`` lines and blank lines are skipped; one non-numeric header line is allowed
    before the data.  Errors name the file and line.

    Parameters
    ----------
    path : str or Path
    kind : str
        What the file is, for messages ("road", "path").
    columns : str
        What a data line holds, for messages (e.g. "'x, y' in metres").

    Returns
    -------
    rows : list of (line_number, text, values)
        ``values`` is a list of finite floats.
    """
    import math

    from flexpipe.errors import InputError

    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the {kind} file ({exc})", file=path) from None
    try:
        lines = raw.decode("utf-8").splitlines()
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); a {kind} file is a "
                         f"text table of {columns}", file=path,
                         line=raw[: exc.start].count(b"\n") + 1) from None
    rows = []
    header_allowed = True
    for k, raw in enumerate(lines, start=1):
        text = raw.strip()
        if not text or text.startswith("#"):
            continue
        fields = [f.strip() for f in (text.split(",") if "," in text else text.split())]
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if header_allowed:
                header_allowed = False
                continue
            raise InputError(f"not a number in {text!r}; expected {columns}",
                             file=path, line=k) from None
        header_allowed = False
        if not all(math.isfinite(v) for v in values):
            raise InputError(f"non-finite value in {text!r}; every value must be a finite "
                             "number", file=path, line=k)
        rows.append((k, text, values))
    return rows


# --------------------------------------------------------------------------- output paths
def _first_existing(path: Path) -> Path:
    for p in (path, *path.parents):
        if p.exists():
            return p
    return Path(".")


def _check_creatable(path: Path, start: Path, option: str, what: str) -> None:
    """The first existing folder from ``start`` up must be a writable folder."""
    from flexpipe.errors import InputError

    anc = _first_existing(start)
    if not anc.is_dir():
        raise InputError(f"{anc} is a file, not a folder: the {what} {path} cannot be "
                         f"created in it; choose another {option}", file=path, key=option)
    if not os.access(anc, os.W_OK | os.X_OK):
        raise InputError(f"no permission to create the {what} in {anc}; choose another "
                         f"{option}", file=path, key=option)


def check_output_folder(out, *, option: str = "--out") -> Path:
    """Check, before any work, that the output folder ``out`` can be written.

    ``out`` must be an existing folder or a path whose first existing ancestor is a
    writable folder.  Commands call this first so that an analysis never runs only to
    fail on its output path.

    Parameters
    ----------
    out : str or Path
        The output folder.
    option : str
        The option or key that gave it (``--out``, ``-o``), named in the error.

    Raises
    ------
    InputError
        ``out`` is an existing file, lies under a file, or its parent is not writable.
    """
    from flexpipe.errors import InputError

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"exists and is a file; {option} takes a folder (the command writes "
                         "several files into it): give a new or existing folder",
                         file=out, key=option)
    _check_creatable(out, out, option, "folder")
    return out


def check_output_file(path, *, option: str = "-o") -> Path:
    """Check, before any work, that the output file ``path`` can be written (it is not an
    existing folder and its folder can be created).

    Raises
    ------
    InputError
        ``path`` is an existing folder, lies under a file, or its parent is not writable.
    """
    from flexpipe.errors import InputError

    path = Path(path)
    if path.is_dir():
        raise InputError(f"is an existing folder; {option} takes a file name", file=path,
                         key=option)
    _check_creatable(path, path.parent, option, "file")
    return path


# --------------------------------------------------------------------------- staged folders
def failed_folder(out) -> Path:
    """``OUT.failed`` next to the output folder ``out``: where a run that failed or was
    interrupted leaves its own ``summary.json`` (and the files of the parts that
    finished), so that ``out`` keeps the last successful run."""
    out = Path(out).resolve()
    return out.parent / f"{out.name}.failed"


def _check_replaceable(folder: Path, option: str) -> None:
    from flexpipe.errors import InputError

    if not folder.exists():
        return
    if not folder.is_dir():
        raise InputError(f"exists and is a file; {option} takes a folder: choose another "
                         f"{option}", file=folder, key=option)
    entries = [e.name for e in folder.iterdir()]
    if entries and "summary.json" not in entries:
        raise InputError(
            f"the folder exists and is not a previous flexpipe run (no summary.json; it holds "
            f"{sorted(entries)[:3]}); a run replaces its output folder (and OUT.failed) as a "
            f"whole: choose a new or empty folder as {option}", file=folder, key=option)


def check_run_folder(out, *, option: str = "--out") -> Path:
    """Check that a run may write ``out`` and ``OUT.failed``: each is absent, empty or a
    previous run's folder (holds a ``summary.json``), and can be created.

    Raises
    ------
    InputError
        One of them is a file or a folder of other files, or cannot be created.
    """
    out = Path(out)
    _check_replaceable(out, option)
    _check_replaceable(failed_folder(out), option)
    check_output_folder(out, option=option)
    return out


def stage_directory(out) -> Path:
    """A fresh, empty staging folder ``.NAME.staging-PID`` next to the output folder ``out``.

    Checks first (:func:`check_run_folder`) that ``out`` and ``OUT.failed`` are absent,
    empty or a previous run's folder, so that :func:`commit_directory` never replaces a
    folder of the user's other files.  Staging folders left by processes that no longer
    exist are removed.

    Raises
    ------
    InputError
        ``out`` is a file, or a folder holding files that are not a flexpipe run.
    """
    return staging_folder(check_run_folder(out))


def staging_folder(dest) -> Path:
    """An empty staging folder ``.NAME.staging-PID`` next to ``dest`` (created with its
    parent); staging folders left by processes that no longer run are removed."""
    import shutil

    dest = Path(dest)
    parent = dest.resolve().parent
    parent.mkdir(parents=True, exist_ok=True)
    for old in parent.glob(f".{dest.name}.staging-*"):
        pid = old.name.rsplit("-", 1)[-1]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(old, ignore_errors=True)
    stage = parent / f".{dest.name}.staging-{os.getpid()}"
    shutil.rmtree(stage, ignore_errors=True)
    stage.mkdir()
    return stage


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def commit_directory(stage, out) -> Path:
    """Put the staging folder ``stage`` in place of ``out`` (the old folder is removed).

    The swap is two renames on the same file system with SIGINT/SIGTERM blocked, so
    ``out`` never holds files of two runs.
    """
    import shutil
    import signal

    stage, out = Path(stage), Path(out)
    old = out.resolve().parent / f".{out.name}.old-{os.getpid()}"
    shutil.rmtree(old, ignore_errors=True)
    blocked = {signal.SIGINT, signal.SIGTERM}
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, blocked)
    try:
        if out.exists():
            os.replace(out, old)
        os.replace(stage, out)
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)
    shutil.rmtree(old, ignore_errors=True)
    return out
