"""Dotted-key overrides on a parsed TOML document, applied before validation.

``corners.fl.spring_rate_N_per_m = 35000`` sets one key of a car file without knowing its
schema: every table on the way must exist in the document (an array of tables is entered
by index, ``body.mass.0.mass_kg``, or by its ``name`` entry, ``body.mass.driver.mass_kg``);
the last key may be new, and the validator of the file (e.g. :func:`flexpipe.load_car`)
then accepts or rejects it like any key written in the file.
"""

from __future__ import annotations

import copy

from flexpipe.errors import InputError


def _child(node, part: str, done: str, file, origin: str):
    if isinstance(node, dict):
        if part in node:
            return node[part]
        valid = ", ".join(sorted(node)) or "(empty table)"
        raise InputError(f"{origin}: there is no table or key '{done + part}' in the file; "
                         f"valid names under [{done.rstrip('.') or 'top level'}]: {valid}",
                         file=file, key=done + part)
    if isinstance(node, list):
        if part.isdigit() and int(part) < len(node):
            return node[int(part)]
        names = [item.get("name") for item in node if isinstance(item, dict)]
        if part in names:
            return node[names.index(part)]
        raise InputError(f"{origin}: '{done.rstrip('.')}' is an array of {len(node)} tables; "
                         f"enter it by index 0..{len(node) - 1} or by name "
                         f"({', '.join(str(n) for n in names if n is not None) or 'none'})",
                         file=file, key=done + part)
    raise InputError(f"{origin}: '{done.rstrip('.')}' is a value ({node!r}), not a table",
                     file=file, key=done + part)


def apply_overrides(doc: dict, overrides: dict, *, file=None, origin: str = "override") -> dict:
    """A deep copy of ``doc`` with every ``{"a.b.c": value}`` of ``overrides`` set.

    Parameters
    ----------
    doc : dict
        Parsed TOML document.
    overrides : dict
        Dotted key to new value (TOML types: number, string, bool, list, table).
    file : str or Path, optional
        The document's file, named in errors.
    origin : str
        Where the overrides come from (e.g. ``"sweep.toml parameter"``), named in errors.

    Raises
    ------
    InputError
        A table on the way does not exist (the message lists the valid names), or a value
        would replace a whole table.
    """
    out = copy.deepcopy(doc)
    for dotted, value in overrides.items():
        parts = str(dotted).split(".")
        if not parts or any(not p for p in parts):
            raise InputError(f"{origin}: malformed dotted key {dotted!r}", file=file,
                             key=str(dotted))
        node, done = out, ""
        for part in parts[:-1]:
            node = _child(node, part, done, file, origin)
            done += part + "."
        last = parts[-1]
        if isinstance(node, list):
            idx = _child(node, last, done, file, origin)  # validates; lists only hold tables
            raise InputError(f"{origin}: '{dotted}' names a whole table ({type(idx).__name__}) "
                             "of an array; set one of its keys instead", file=file, key=dotted)
        if not isinstance(node, dict):
            raise InputError(f"{origin}: '{done.rstrip('.')}' is a value, not a table",
                             file=file, key=dotted)
        old = node.get(last)
        if isinstance(old, dict | list) and not isinstance(value, type(old)):
            keys = ", ".join(sorted(old)) if isinstance(old, dict) else "by index"
            raise InputError(f"{origin}: '{dotted}' is a table in the file; set one of its keys "
                             f"({keys}) instead of replacing it with {value!r}", file=file,
                             key=dotted)
        node[last] = copy.deepcopy(value)
    return out


__all__ = ["apply_overrides"]
