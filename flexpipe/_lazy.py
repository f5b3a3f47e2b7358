"""Lazy re-exports for package ``__init__`` modules (imports happen on first use)."""

from __future__ import annotations

import importlib


def lazy_exports(package: str, exports: dict, extra=()):
    """``(__getattr__, __dir__, __all__)`` for a package exporting ``{name: module}``
    (``extra``: names the package defines itself)."""
    names = sorted(exports) + list(extra)

    def __getattr__(name):
        if name in exports:
            return getattr(importlib.import_module(exports[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return names

    return __getattr__, __dir__, names
