"""numkin.bench's build rows measure what they say: a sympy build with an empty kernel cache, then a cache read."""

from __future__ import annotations

import math

import numpy as np

from numkin import bench, kernel_cache


def test_build_times_compile_in_an_empty_cache_then_read_it(monkeypatch, tmp_path):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path))
    theta = np.radians(np.arange(0.0, 361.0))
    compiled, cached, mech = bench.build_times(theta)
    assert compiled > 0 and math.isfinite(cached) and cached > 0  # the new process wrote a bundle, read here
    assert kernel_cache.cache_dir() == tmp_path  # the caller's cache setting is restored
    assert not any(tmp_path.iterdir())  # the build used its own temporary cache, not the caller's
    diff = np.angle(np.exp(1j * (mech.sweep(theta).values - bench.closed_form_sweep(theta))))
    assert np.max(np.abs(diff)) < 1e-10


def test_build_times_with_the_cache_turned_off(monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, "off")
    compiled, cached, _ = bench.build_times(np.radians([0.0, 1.0]))
    assert compiled > 0 and math.isfinite(cached)
    assert kernel_cache.cache_dir() is None
