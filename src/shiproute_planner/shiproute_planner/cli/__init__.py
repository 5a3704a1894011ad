"""Command-line subcommands registered in the ``shiproute.commands`` entry-point group."""
