"""Car variants: a car file that names a ``base`` car file and changes some of its keys.

::

    # cars/variants/sedan_soft_front.toml
    base = "../sedan_linkage.toml"          # relative to this file

    [suspension.front.spring]
    rate_N_per_m = 30000.0

A variant is the base file's document with the variant's keys set on it: a table merges
into the base's table key by key, any other value (a number, a string, a list, a list of
tables such as ``[[body.mass]]``) replaces the base's.  A base may itself name a base (up
to :data:`MAX_DEPTH` files).  The base's file paths (``corners.<c>.tire``, ``body.mesh``,
``body.body_file``) stay relative to the base's folder; the variant's own relative to its
folder.  ``[car] name`` is not inherited: a variant is named by its own file unless it
says otherwise.  Errors about a key only a base writes name that base file and line.
"""

from __future__ import annotations

from pathlib import Path

from flexpipe.errors import InputError
from flexpipe.vehicle._toml import Table, parse

#: the top-level key naming the base car file
BASE_KEY = "base"
#: most files in a chain of bases (the variant included)
MAX_DEPTH = 8
#: keys holding file paths, relative to the file that writes them ("*": any table)
PATH_KEYS = (("corners", "*", "tire"), ("body", "mesh"), ("body", "body_file"))


def parse_car(path: Path) -> tuple[dict, list[str], tuple]:
    """The document of car file ``path`` with its bases merged in.

    Returns
    -------
    doc : dict
        Merged document (without ``base``).
    lines : list of str
        ``path``'s own text.
    fallbacks : tuple of (Path, list of str)
        The base files and their text, nearest first (for :class:`Table`).

    Raises
    ------
    InputError
        A ``base`` that is not a string naming an existing ``.toml`` file, a cycle or a
        chain longer than :data:`MAX_DEPTH`, or a key that is a table in one file and a
        value in the other; naming the file, line and key.
    """
    path = Path(path)
    doc, lines = parse(path)
    merged, fallbacks = _with_bases(path, doc, lines, [path.resolve()])
    return merged, lines, tuple(fallbacks)


def car_files(path: Path) -> list[Path]:
    """``path`` and the base files it builds on (nearest first); ``[path]`` when it cannot
    be read (its loader reports why)."""
    try:
        return [Path(path)] + [f for f, _ in parse_car(Path(path))[2]]
    except InputError:
        return [Path(path)]


def _with_bases(path: Path, doc: dict, lines: list[str], chain: list[Path]):
    if BASE_KEY not in doc:
        return doc, []
    top = Table(doc, "", path, lines)
    value = doc.pop(BASE_KEY)
    if not isinstance(value, str) or not value.strip():
        raise top.error(BASE_KEY, f"expected the base car file as a string (a path relative "
                                  f"to this file), got {value!r}")
    base = (path.parent / value).resolve()
    if base.suffix.lower() != ".toml" or not base.is_file():
        raise top.error(BASE_KEY, f"base car file {base} "
                                  + ("is no .toml file" if base.suffix.lower() != ".toml"
                                     else "does not exist") + " (paths are relative to "
                                  f"{path.parent})")
    if base in chain:
        raise top.error(BASE_KEY, "the bases form a cycle: " + " -> ".join(
            str(f) for f in [*chain, base]))
    if len(chain) >= MAX_DEPTH:
        raise top.error(BASE_KEY, f"more than {MAX_DEPTH} files in the chain of bases: "
                                  + " -> ".join(str(f) for f in [*chain, base]))
    bdoc, blines = parse(base)
    bdoc, bfall = _with_bases(base, bdoc, blines, [*chain, base])
    _absolute_paths(bdoc, base.parent)
    own_name = isinstance(doc.get("car"), dict) and "name" in doc["car"]
    if not own_name and isinstance(bdoc.get("car"), dict):
        bdoc["car"].pop("name", None)
    return _merge(bdoc, doc, "", top), [(base, blines), *bfall]


def _absolute_paths(doc: dict, folder: Path) -> None:
    """The base's file paths made absolute (they are relative to its own folder)."""
    for keys in PATH_KEYS:
        tables = [doc]
        for k in keys[:-1]:
            nxt = []
            for t in tables:
                if k == "*":
                    nxt += [v for v in t.values() if isinstance(v, dict)]
                elif isinstance(t.get(k), dict):
                    nxt.append(t[k])
            tables = nxt
        for t in tables:
            v = t.get(keys[-1])
            if isinstance(v, str) and v.strip():
                t[keys[-1]] = str((folder / v).resolve())


def _merge(base: dict, over: dict, name: str, top: Table) -> dict:
    """``over`` set on ``base`` (tables merged key by key, other values replaced)."""
    for k, v in over.items():
        dotted = f"{name}.{k}" if name else k
        if k in base and isinstance(base[k], dict) != isinstance(v, dict):
            what = "a table" if isinstance(base[k], dict) else "a value"
            line = (Table(over, name, top.file, top.lines)._key_line(k)
                    or Table({}, dotted, top.file, top.lines)._line(None))
            raise InputError(f"'{dotted}' is {what} in the base car file, so the variant "
                             f"must give {what} too, got {v!r:.60}", file=top.file,
                             line=line, key=dotted)
        base[k] = _merge(base[k], v, dotted, top) if isinstance(v, dict) and k in base else v
    return base
