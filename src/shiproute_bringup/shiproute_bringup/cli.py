"""The umbrella `shiproute` command: dispatches to subcommands registered by all packages."""

from __future__ import annotations

import os
import sys

from shiproute_bringup.dispatch import dispatch

GROUP = "shiproute.commands"


def main(argv: list[str] | None = None) -> int:
    """Console-script entry: ``shiproute <subcommand> [args...]``."""
    args = sys.argv[1:] if argv is None else argv
    try:
        return dispatch("shiproute", GROUP, args, what="subcommand")
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # output piped into e.g. `head`: stop quietly, like other Unix tools
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141


if __name__ == "__main__":
    sys.exit(main())
