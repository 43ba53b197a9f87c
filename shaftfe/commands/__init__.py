"""CLI command groups. Each module: ``register(subparsers)``; stdlib-only imports at top level."""
