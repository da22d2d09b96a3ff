"""``python -m plumbob``: the same as the ``plumbob`` command."""

import sys

from .cli import main

sys.exit(main())
