"""The release, in one place: ``pyproject.toml`` reads it from here, ``plumbob.__version__``
and ``plumbob --version`` show it (an uninstalled source tree knows its version too)."""

__version__ = "0.2.0"
