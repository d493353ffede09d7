"""``hairbrush`` subcommand groups; each module has ``register(subparsers)``."""
