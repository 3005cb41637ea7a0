"""ctest's python.module: pytest on this folder, or exit status 77 (skipped) without pytest or
pandas (python3-pytest, python3-pandas)."""

import os
import sys

try:
    import pandas  # noqa: F401
    import pytest
except ImportError as missing:
    print("skipped:", missing)
    sys.exit(77)

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", os.path.dirname(__file__)]))
