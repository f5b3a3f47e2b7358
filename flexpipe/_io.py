"""Small I/O helpers: atomic writes so that no output is ever half-written."""

from __future__ import annotations

import contextlib
import dataclasses
import os
import re
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


#: length units a table header may name (factor to metres)
LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "km": 1e3}
_BRACKET_UNIT = re.compile(r"^(?P<name>.*?)\s*[\[(]\s*(?P<unit>[^\])]*?)\s*[\])]$")
_HEADER_FIELD = re.compile(r"[^\s\[(]+(?:\s*[\[(][^\])]*[\])])?")


def _split_fields(text: str) -> list[str]:
    return [f.strip() for f in (text.split(",") if "," in text else text.split())]


def _split_header(text: str) -> list[str]:
    """Header fields: comma separated, or whitespace separated with ``name [unit]`` kept
    together."""
    if "," in text:
        return [f.strip().strip('"').strip("'").strip() for f in text.split(",")]
    return _HEADER_FIELD.findall(text)


def _is_number(field: str) -> bool:
    try:
        float(field)
    except ValueError:
        return False
    return True


@dataclasses.dataclass(frozen=True)
class NumericTable:
    """A small numeric table read by :func:`read_numeric_table`.

    Attributes
    ----------
    header : list of str or None
        The fields of the header line (None when the file has none).
    header_line : int or None
        Its line number.
    rows : list of (line_number, text, values)
        The data lines; ``values`` is a list of finite floats.
    """

    header: list | None
    header_line: int | None
    rows: list


def read_numeric_table(path, *, kind: str, columns: str) -> NumericTable:
    """Read a small numeric table (comma or whitespace separated) with line numbers.

    The file is UTF-8 text (a UTF-8 byte order mark is skipped).  ``#`` lines and blank
    lines are skipped; the first other line is a header when none of its fields is a
    number (column names, returned for the caller to interpret, see
    :func:`header_columns`); every other line is data.  Errors name the file and line.

    Parameters
    ----------
    path : str or Path
    kind : str
        What the file is, for messages ("road", "path").
    columns : str
        What a data line holds, for messages (e.g. "'x, y' in metres").

    Returns
    -------
    NumericTable
    """
    import math

    from flexpipe.errors import InputError

    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the {kind} file ({exc})", file=path) from None
    try:
        lines = raw.decode("utf-8-sig").splitlines()
    except UnicodeDecodeError as exc:
        at = exc.start + (3 if raw.startswith(b"\xef\xbb\xbf") else 0)
        raise InputError(f"not UTF-8 text (byte 0x{raw[at]:02x}); a {kind} file is a "
                         f"text table of {columns}", file=path,
                         line=raw[:at].count(b"\n") + 1) from None
    rows = []
    header = header_line = None
    first = True
    for k, line in enumerate(lines, start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        fields = _split_fields(text)
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if first and not any(_is_number(f) for f in fields):
                header, header_line = _split_header(text), k
                first = False
                continue
            raise InputError(f"not a number in {text!r}; expected {columns}",
                             file=path, line=k) from None
        first = False
        if not all(math.isfinite(v) for v in values):
            raise InputError(f"non-finite value in {text!r}; every value must be a finite "
                             "number", file=path, line=k)
        rows.append((k, text, values))
    return NumericTable(header=header, header_line=header_line, rows=rows)


def read_numeric_rows(path, *, kind: str, columns: str):
    """The data lines of :func:`read_numeric_table` (its header, if any, is dropped):
    a list of ``(line_number, text, values)``."""
    return read_numeric_table(path, kind=kind, columns=columns).rows


def _column_key(name: str) -> str:
    return re.sub(r"[\s\-]+", "_", name.strip().lower()).strip("_")


def header_columns(header, *, names: dict, file, line: int | None, kind: str) -> list:
    """What each column of a table header is, and the factor from its unit to metres.

    A field is a column name, optionally with a length unit: ``x``, ``x_m``, ``x_mm``,
    ``x [mm]``, ``x (m)``, ``x m`` (case, spaces and hyphens in names do not matter; the
    units are those of :data:`LENGTH_UNITS`, metres when none is given).

    Parameters
    ----------
    header : list of str
        The header fields (:attr:`NumericTable.header`).
    names : dict
        ``{role: (name, ...)}``: the names each role of a column may have, e.g.
        ``{"x": ("x",), "y": ("y",)}``.
    file, line
        Where the header is, for messages.
    kind : str
        What the file is ("road", "path"), for messages.

    Returns
    -------
    list of (role, factor)
        One per field.

    Raises
    ------
    InputError
        Naming the file, line and column: a unit that is not a length unit listed above,
        a name no role has (the message lists the valid names), or a role given twice.
    """
    from flexpipe.errors import InputError

    lookup = {_column_key(n): role for role, ns in names.items() for n in ns}
    valid = "; ".join(f"{role}: {', '.join(ns)}" for role, ns in names.items())
    units = ", ".join(LENGTH_UNITS)
    out, seen = [], {}
    for i, field in enumerate(header, start=1):
        where = dict(file=file, line=line, key=field)
        m = _BRACKET_UNIT.match(field)
        if m:
            name, unit = _column_key(m.group("name")), m.group("unit").strip()
            if name not in lookup:
                raise InputError(f"{kind} file header: column {i} {field!r} is not a column "
                                 f"a {kind} has; valid names ({valid}), each optionally with "
                                 f"a unit ({units}) as name_mm or name [mm]", **where)
        else:
            name, unit = _column_key(field), None
            if name not in lookup:
                head, _, tail = name.rpartition("_")
                if head in lookup:
                    name, unit = head, tail
                else:
                    raise InputError(
                        f"{kind} file header: column {i} {field!r} is not a column a {kind} "
                        f"has; valid names ({valid}), each optionally with a unit ({units}) "
                        "as name_mm or name [mm]", **where)
        if unit is not None and unit.lower() not in LENGTH_UNITS:
            raise InputError(f"{kind} file header: column {i} {field!r} is in {unit!r}, not "
                             f"a length unit flexpipe knows; valid units: {units}", **where)
        role = lookup[name]
        if role in seen:
            raise InputError(f"{kind} file header: column {i} {field!r} is the {role} again "
                             f"(column {seen[role]} {header[seen[role] - 1]!r}); each column "
                             "once", **where)
        seen[role] = i
        out.append((role, 1.0 if unit is None else LENGTH_UNITS[unit.lower()]))
    return out


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
