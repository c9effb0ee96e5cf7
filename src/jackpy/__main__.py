"""``python -m jackpy`` runs the ``jackpy`` command."""

import sys

from jackpy.cli import main

sys.exit(main())
