"""The disk cache of generated kernels: hits across runs, rebuilt when corrupt, stale or tampered with."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from numkin import kernel_cache

BUILD = (
    "import numpy as np\n"
    "from numkin import linkages\n"
    "m = linkages.chained_four_bars()\n"
    "s = m.sweep(np.radians(np.arange(0, 361.0)))\n"
    "np.save(r'{out}', s.values)\n"
)
NO_LAMBDIFY = (
    "import sympy\n"
    "def refuse(*a, **k):\n"
    "    raise AssertionError('sympy.lambdify called although the kernels are cached')\n"
    "sympy.lambdify = refuse\n"
    "import sympy.utilities.lambdify as L\n"
    "L.lambdify = refuse\n"
)


def run(code, folder, check=True):
    env = dict(os.environ, NUMKIN_CACHE_DIR=str(folder))
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=check)


def entries(folder: Path):
    return sorted(p for p in folder.glob("*.json"))


def test_second_run_reuses_every_kernel_with_the_same_numbers(tmp_path):
    folder = tmp_path / "kernels"
    run(BUILD.format(out=tmp_path / "first.npy"), folder)
    assert len(entries(folder)) >= 6
    run(NO_LAMBDIFY + BUILD.format(out=tmp_path / "second.npy"), folder)
    np.testing.assert_array_equal(np.load(tmp_path / "first.npy"), np.load(tmp_path / "second.npy"))
    run(BUILD.format(out=tmp_path / "off.npy"), "off")
    np.testing.assert_array_equal(np.load(tmp_path / "first.npy"), np.load(tmp_path / "off.npy"))


@pytest.mark.parametrize("damage", ["garbage", "stale key", "tampered source", "attribute access"])
def test_a_bad_entry_is_rebuilt_never_trusted(tmp_path, damage):
    folder = tmp_path / "kernels"
    run(BUILD.format(out=tmp_path / "first.npy"), folder)
    for path in entries(folder):
        entry = json.loads(path.read_text())
        if damage == "garbage":
            path.write_text("{not json")
            continue
        if damage == "stale key":
            entry["key"] = "0" * 64
        elif damage == "tampered source":
            entry["source"] = entry["source"].replace("return", "import os; return", 1)
        else:  # a checksum that matches, code that reaches outside
            entry["source"] = entry["source"].replace("return [", "return [().__class__, ", 1)
            import hashlib

            entry["sha256"] = hashlib.sha256(entry["source"].encode()).hexdigest()
        path.write_text(json.dumps(entry))
    out = run(BUILD.format(out=tmp_path / "again.npy"), folder)
    assert out.returncode == 0, out.stderr
    np.testing.assert_array_equal(np.load(tmp_path / "first.npy"), np.load(tmp_path / "again.npy"))
    for path in entries(folder):  # rewritten valid
        entry = json.loads(path.read_text())
        assert entry["key"] == path.stem and "import" not in entry["source"]


def test_concurrent_runs_leave_whole_entries(tmp_path):
    folder = tmp_path / "kernels"
    env = dict(os.environ, NUMKIN_CACHE_DIR=str(folder))
    procs = [subprocess.Popen([sys.executable, "-c", BUILD.format(out=tmp_path / f"p{k}.npy")], env=env)
             for k in range(3)]
    assert [p.wait(timeout=300) for p in procs] == [0, 0, 0]
    for path in entries(folder):
        json.loads(path.read_text())
    assert not list(folder.glob(".tmp-*"))
    run(NO_LAMBDIFY + BUILD.format(out=tmp_path / "after.npy"), folder)


def test_cache_folder_from_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path / "here"))
    assert kernel_cache.cache_dir() == tmp_path / "here"
    monkeypatch.setenv(kernel_cache.ENV_VAR, "off")
    assert kernel_cache.cache_dir() is None
    monkeypatch.delenv(kernel_cache.ENV_VAR)
    assert kernel_cache.cache_dir().parts[-2:] == ("numkin", "kernels") or "numkin" in str(kernel_cache.cache_dir())


def test_unwritable_folder_costs_only_the_cache(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    out = run(BUILD.format(out=tmp_path / "x.npy"), blocker / "kernels")
    assert out.returncode == 0, out.stderr
