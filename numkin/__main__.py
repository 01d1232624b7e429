"""``python -m numkin``: the ``numkin`` command (see :mod:`numkin.cli`)."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
