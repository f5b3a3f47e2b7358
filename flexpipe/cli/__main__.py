"""``python -m flexpipe.cli`` (the same as the ``flexpipe`` command)."""

from flexpipe.cli import main

raise SystemExit(main())
