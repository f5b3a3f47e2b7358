"""The ``flexpipe`` command line: ``flexpipe COMMAND [options]`` (or ``python -m flexpipe``).

A thin layer over the API: each subcommand is a module of this package
(``flexpipe.cli.run``, ``flexpipe.cli.reduce``, ...) that parses its options and calls
the pipeline's functions.  Subcommands are listed in :data:`COMMANDS` as
``(name, module, one-line help)`` and imported only when used, so ``flexpipe --help``
stays fast.  A command module provides

``add_arguments(parser)``
    add its options to an :class:`argparse.ArgumentParser` (``prog`` is already
    ``flexpipe NAME``);
``run(args) -> int | None``
    do the work; the return value is the exit code (None means 0).

Any :class:`~flexpipe.errors.FlexpipeError` or ``OSError`` a command raises is printed
as a one-line message without traceback, with exit code 2 (argparse usage errors also
exit with 2); Ctrl-C and SIGTERM stop the command with exit code 130 / 143; warnings
are printed as one line each.  To add a command, append a line to :data:`COMMANDS`.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import sys
import warnings

#: (name, module, help) of every subcommand; modules that are not installed are hidden
COMMANDS = (
    ("modes", "flexpipe.cli.modes", "natural frequencies and mode shapes of a mesh (.vtu)"),
    ("info", "flexpipe.cli.info", "summary of a mesh, body, car, road or path file"),
    ("reduce", "flexpipe.cli.reduce", "component mode synthesis of a mesh into a flexible body"),
    ("run", "flexpipe.cli.run", "simulate a car scenario"),
    ("kc", "flexpipe.cli.kc", "kinematics and compliance rig of a car's suspension"),
    ("linear", "flexpipe.cli.linear", "linear modes of the whole car (frequencies, damping)"),
    ("ride", "flexpipe.cli.ride", "ride comfort and tyre load on an ISO 8608 road vs speed"),
    ("stress", "flexpipe.cli.stress", "stress recovery, hot spots and fatigue of a run"),
    ("animate", "flexpipe.cli.animate", "ParaView animation (.pvd) of a run's flexible body"),
    ("sweep", "flexpipe.cli.sweep", "many runs from one spec on Dask (table, channels, plots)"),
)
EXIT_ERROR = 2
#: exit code when the reader of the output closed the pipe (128 + SIGPIPE, as a shell's)
EXIT_BROKEN_PIPE = 141


def _available():
    out = []
    for name, module, text in COMMANDS:
        try:
            found = importlib.util.find_spec(module) is not None
        except (ImportError, ValueError):
            found = False
        if found:
            out.append((name, module, text))
    return out


def _top_parser(commands) -> argparse.ArgumentParser:
    from flexpipe import __version__

    listing = "\n".join(f"  {name:<10}{text}" for name, _, text in commands) or "  (none)"
    p = argparse.ArgumentParser(
        prog="flexpipe",
        description="flexpipe: meshed car body -> FE -> component mode synthesis -> "
                    "Exudyn flexible body -> full car.",
        epilog=f"commands:\n{listing}\n\nRun 'flexpipe COMMAND --help' for a command's options.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--version", action="version", version=f"flexpipe {__version__}")
    p.add_argument("command", metavar="COMMAND", choices=[c[0] for c in commands],
                   help="one of: " + ", ".join(c[0] for c in commands))
    return p


def _one_line(exc: BaseException) -> str:
    """The error as one line: its message, then its notes (e.g. where a failed run left
    its summary) in parentheses."""
    text = str(exc) or type(exc).__name__
    if isinstance(exc, OSError) and exc.filename:
        text = f"{exc.filename}: {exc.strerror or text}"
    return " ".join((text + _notes(exc)).split())


def _notes(exc: BaseException) -> str:
    notes = getattr(exc, "__notes__", None) or []
    return f" ({'; '.join(notes)})" if notes else ""


def _quiet_stdout() -> None:
    """Point stdout at /dev/null, so that the interpreter's final flush of a closed pipe
    does not print a second error."""
    import os

    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):  # no real stdout (e.g. captured in a test)
        pass


def main(argv=None) -> int:
    """Entry point of the ``flexpipe`` console script; returns the exit code."""
    from flexpipe.errors import FlexpipeError

    argv = list(sys.argv[1:] if argv is None else argv)
    commands = _available()
    top = _top_parser(commands)
    if argv and argv[0].startswith("-") and argv[0] not in ("-h", "--help", "--version"):
        top.print_usage(sys.stderr)
        print(f"flexpipe: error: unknown option {argv[0]}; give a COMMAND first: "
              f"{', '.join(c[0] for c in commands)} (options follow the command)",
              file=sys.stderr)
        return EXIT_ERROR
    try:
        ns = top.parse_args(argv[:1] if argv and not argv[0].startswith("-") else argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    name = ns.command
    module_name, text = next((m, t) for n, m, t in commands if n == name)
    module = importlib.import_module(module_name)
    parser = argparse.ArgumentParser(prog=f"flexpipe {name}", description=text)
    module.add_arguments(parser)
    try:
        args = parser.parse_args(argv[1:])
    except SystemExit as exc:
        return int(exc.code or 0)
    def show_warning(message, category, filename, lineno, file=None, line=None):
        print(f"flexpipe {name}: warning: {' '.join(str(message).split())}", file=sys.stderr)

    from flexpipe._signals import interrupt_info, interrupt_text, interrupts_as_exceptions

    try:
        with warnings.catch_warnings(), interrupts_as_exceptions():
            warnings.showwarning = show_warning
            code = module.run(args)
    except BrokenPipeError:  # the reader of the output left (``flexpipe info ... | head``)
        _quiet_stdout()
        return EXIT_BROKEN_PIPE
    except (FlexpipeError, OSError) as exc:
        print(f"flexpipe {name}: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt as exc:
        print(f"flexpipe {name}: {interrupt_text(exc)}{_notes(exc)}", file=sys.stderr)
        return interrupt_info(exc)[0]
    return int(code or 0)

