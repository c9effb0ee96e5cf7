"""Subcommands of the ``jackpy`` CLI, one module each, each exporting ``register(subparsers)``."""
