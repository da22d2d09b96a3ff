"""Reader-side checks: plausible sizes, absurd coordinates; units and their notices."""

import numpy as np
import pytest

from plumbob import units
from plumbob.errors import GeometryError
from plumbob.io.checks import check_extent
from plumbob.units import units_scale


def test_extent_and_units():
    assert check_extent(np.zeros(3), np.ones(3), path=None) == ()
    assert "2000 m across" in check_extent(np.zeros(2), np.array([2000.0, 0]), path=None)[0]
    assert "only 1e-06 m" in check_extent(np.zeros(2), np.array([1e-6, 0]), path=None)[0]
    with pytest.raises(GeometryError, match="far beyond"):
        check_extent(np.zeros(3), np.array([0, 0, 2e9]), path="x.stl")
    assert units_scale(None) == (1.0, (units.UNITS_ASSUMED,))
    assert units_scale("in") == (0.0254, ())
    assert units_scale(None, "millimeter", 1e-3)[0] == 1e-3
