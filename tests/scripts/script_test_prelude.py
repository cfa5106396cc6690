"""What the script tests in tests/scripts share: the repository root, the
fixture folders under tests/fixtures, and scripts/ on the import path (the
scripts under test are imported as modules)."""
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
if os.path.join(ROOT, "scripts") not in sys.path:
    sys.path.insert(0, os.path.join(ROOT, "scripts"))


def fixture(name):
    """The folder tests/fixtures/<name>."""
    return os.path.join(ROOT, "tests", "fixtures", name)
