"""One module per ``steakhouse`` subcommand; each exposes ``register(subparsers)``.

A handler is ``handler(args) -> int`` and is attached with ``set_defaults(handler=..., subparser=...)``.
"""
