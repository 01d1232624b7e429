"""The test session's kernel cache is a temporary folder, never the user's."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def test_cache_dir_is_a_session_temporary_folder():
    from numkin import kernel_cache

    where = kernel_cache.cache_dir()
    assert os.environ["NUMKIN_CACHE_DIR"] == str(where)
    assert Path(where).resolve().is_relative_to(Path(tempfile.gettempdir()).resolve())
    assert Path(where).name.startswith("numkin-test-cache-")
