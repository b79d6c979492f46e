"""The examples in the package's docstrings run as written."""

import doctest

import matplotlib

matplotlib.use("Agg")

import sightline  # noqa: E402
import sightline.mpl  # noqa: E402


def test_docstring_examples_run():
    for module in (sightline, sightline.mpl):
        failed, tried = doctest.testmod(module)
        assert tried > 0 and failed == 0, module.__name__
