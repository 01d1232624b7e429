"""Benchmarks of numkin: times and ratios against the closed form, a hand-written vectorised Newton,
the textbook code, and other kinematics packages when they are installed.

Run ``python -m benchmarks [--quick] [--output FILE]`` from the repository root
(or ``python benchmarks/run.py``); see ``benchmarks/README.md``.
"""
