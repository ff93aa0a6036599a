"""``python -m shintai`` is the ``shintai`` command."""

import sys

from shintai.cli import main

sys.exit(main())
