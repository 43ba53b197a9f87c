import sys

from shaftfe.cli import main

sys.exit(main())
