from __future__ import annotations

from pathlib import Path

import pytest

REAL_BAGS = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "real_bags"


@pytest.fixture
def real_bags() -> Path:
    if not REAL_BAGS.is_dir():
        pytest.skip("shared/data/real_bags is not beside this checkout")
    return REAL_BAGS
