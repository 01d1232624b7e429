"""Test configuration: a private kernel cache, and reproducible property tests in continuous integration.

The suite never writes the user's cache of compiled kernels: ``NUMKIN_CACHE_DIR``
points at a temporary folder made for this test session and removed after it
(the kernel cache's own tests set theirs).

Locally hypothesis draws fresh examples on every run; with the environment
variable ``CI`` set it draws the same examples every time, so a submission is
judged on a fixed set of linkages.
"""

import os
import shutil
import tempfile

from hypothesis import settings

_CACHE = tempfile.mkdtemp(prefix="numkin-test-cache-")
os.environ["NUMKIN_CACHE_DIR"] = _CACHE


def pytest_sessionfinish(session, exitstatus):
    shutil.rmtree(_CACHE, ignore_errors=True)


settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")
