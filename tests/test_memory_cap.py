"""The test processes' address-space cap (tests/conftest.py): a runaway allocation fails
its own test with MemoryError instead of the kernel's OOM killer taking the pytest-xdist
worker down (which once left a CI run hanging at 99 %)."""

from __future__ import annotations

import resource

import numpy as np
import pytest
from conftest import MEMORY_CAP_GB


@pytest.mark.skipif(MEMORY_CAP_GB <= 0, reason="FLEXPIPE_TEST_MEMORY_GB=0: no cap")
def test_an_allocation_beyond_the_cap_is_a_memory_error():
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    assert soft != resource.RLIM_INFINITY and soft <= MEMORY_CAP_GB * 2**30
    with pytest.raises(MemoryError):
        np.empty(int(1.5 * MEMORY_CAP_GB * 2**30) // 8)  # virtual only, were it not capped
