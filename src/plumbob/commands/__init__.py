"""The CLI's subcommands, one module each (see :mod:`plumbob.cli`)."""
