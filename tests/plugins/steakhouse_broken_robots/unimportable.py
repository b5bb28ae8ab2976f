"""A plug-in module that cannot be imported (a dependency its package forgot)."""

import steakhouse_no_such_dependency  # noqa: F401
