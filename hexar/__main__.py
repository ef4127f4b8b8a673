from __future__ import annotations

import sys

from hexar.cli import main

sys.exit(main())
