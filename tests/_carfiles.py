"""Car files for tests: a sample car's text with its relative paths (``"../..."``) made
absolute, so that a changed copy can be written anywhere (e.g. ``tmp_path``)."""

import re
from pathlib import Path


def absolute_text(src: Path) -> str:
    """The text of the car file ``src`` with its relative paths made absolute."""
    return re.sub(r'"(\.\./[^"]+)"', lambda m: f'"{(src.parent / m[1]).resolve()}"',
                  Path(src).read_text())
