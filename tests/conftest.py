"""Test configuration: property tests are reproducible in continuous integration.

Locally hypothesis draws fresh examples on every run; with the environment
variable ``CI`` set it draws the same examples every time, so a submission is
judged on a fixed set of linkages.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")
