"""``python -m shaftfe``: the command line (``shaftfe.cli.main``), as the ``shaftfe`` script."""

import sys

from shaftfe.cli import main

sys.exit(main())
