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


def write_text_atomic(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)


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
        lines = path.read_text().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read the {kind} file ({exc})", file=path) from None
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
