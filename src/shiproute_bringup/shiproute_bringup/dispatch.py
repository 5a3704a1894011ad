"""Entry-point dispatch shared by `shiproute` and `shiproute bench`.

Commands are entry points ``name = module:main`` with ``main(argv: list[str]) -> int``; the help
line is the first line of the module docstring. A module that fails to import is listed with its
error and does not affect the other commands.
"""

from __future__ import annotations

import importlib
import importlib.metadata as md
import sys
from collections.abc import Callable
from dataclasses import dataclass

USAGE_EXIT = 2


@dataclass(frozen=True)
class Command:
    """One registered command: its name and ``module:attr`` target."""

    name: str
    target: str

    @property
    def module_name(self) -> str:
        """Module part of the target."""
        return self.target.split(":", 1)[0]

    def load(self) -> Callable[[list[str]], int]:
        """Import the module and return its main function."""
        module_name, _, attr = self.target.partition(":")
        module = importlib.import_module(module_name)
        return getattr(module, attr or "main")

    def help_line(self) -> str:
        """First docstring line of the module, or the import error when it does not import."""
        try:
            module = importlib.import_module(self.module_name)
        except Exception as exc:
            return f"(unavailable: {type(exc).__name__}: {exc})"
        doc = (module.__doc__ or "").strip()
        return doc.splitlines()[0] if doc else ""


def discover(group: str) -> dict[str, Command]:
    """All entry points of ``group`` by name (first registration wins on duplicates)."""
    found: dict[str, Command] = {}
    for ep in md.entry_points(group=group):
        found.setdefault(ep.name, Command(ep.name, ep.value))
    return dict(sorted(found.items()))


def listing(commands: dict[str, Command], with_help: bool = True) -> str:
    """Aligned ``name  help`` lines (help imports each module; names only skip that)."""
    if not commands:
        return "  (none registered)"
    if not with_help:
        return "  " + " ".join(commands)
    width = max(len(name) for name in commands)
    return "\n".join(f"  {name:<{width}}  {cmd.help_line()}" for name, cmd in commands.items())


def dispatch(prog: str, group: str, argv: list[str], what: str = "command") -> int:
    """Run ``argv[0]`` from ``group`` with the remaining arguments; usage errors exit 2."""
    commands = discover(group)
    head = f"usage: {prog} <{what}> [args...]  ({prog} --help lists them with help)\n"
    short = f"{head}{what}s:\n{listing(commands, with_help=False)}\n"
    if not argv:
        sys.stderr.write(f"{prog}: missing {what}\n{short}")
        return USAGE_EXIT
    if argv[0] in ("-h", "--help", "help"):
        sys.stdout.write(f"usage: {prog} <{what}> [args...]\n\n{what}s:\n{listing(commands)}\n"
                         f"\nRun '{prog} <{what}> --help' for the options of one {what}.\n")
        return 0
    name, rest = argv[0], argv[1:]
    command = commands.get(name)
    if command is None:
        sys.stderr.write(f"{prog}: unknown {what} '{name}'\n{short}")
        return USAGE_EXIT
    try:
        main = command.load()
    except Exception as exc:
        sys.stderr.write(f"{prog}: {what} '{name}' is unavailable: {type(exc).__name__}: {exc}\n")
        return 1
    result = main(rest)
    return int(result or 0)
