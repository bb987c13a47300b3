"""``python -m drillstring.cli``: the ``drillstring`` command."""

import sys

from . import main

sys.exit(main())
