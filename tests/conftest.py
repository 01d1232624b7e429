"""Test configuration: a private kernel cache, reproducible property tests in continuous
integration, and :func:`load_module` for the assignment scripts (not a package).

The suite never writes the user's cache of compiled kernels: ``NUMKIN_CACHE_DIR``
points at a temporary folder made for this test session and removed after it
(the kernel cache's own tests set theirs).

Locally hypothesis draws fresh examples on every run; with the environment
variable ``CI`` set it draws the same examples every time, so a submission is
judged on a fixed set of linkages.
"""

import importlib.util
import os
import shutil
import sys
import tempfile

from hypothesis import settings

_CACHE = tempfile.mkdtemp(prefix="numkin-test-cache-")
os.environ["NUMKIN_CACHE_DIR"] = _CACHE


def pytest_sessionfinish(session, exitstatus):
    shutil.rmtree(_CACHE, ignore_errors=True)


settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


def load_module(name, path):
    """Import the Python file ``path`` as module ``name`` (the assignments folder is no package)."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
