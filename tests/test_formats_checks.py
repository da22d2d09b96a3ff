"""Reader-side checks: plausible sizes, absurd coordinates; units and their notices."""

import numpy as np
import pytest

from plumbob import units
from plumbob.errors import GeometryError
from plumbob.formats.checks import check_extent
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


def test_unitless_model_over_ten_metres_is_called_millimetres():
    from plumbob.formats.checks import ASSUMED_METRES_LIMIT, check_extent

    lo = np.zeros(3)
    tall = np.array([0.04, 0.03, 0.119]) * 1000  # a 119 mm figurine read as metres
    (notice,) = check_extent(lo, tall, path=None, assumed=True)
    assert notice.startswith("size: the model is 40 × 30 × 119 m, implausible for metres")
    assert notice.endswith("pass --units mm")
    assert check_extent(lo, tall, path=None) == ()  # its unit was given: plausible
    at_limit = np.array([ASSUMED_METRES_LIMIT, 1.0, 1.0])
    assert check_extent(lo, at_limit, path=None, assumed=True) == ()


def test_unitless_obj_over_ten_metres_gets_the_notice(tmp_path):
    from plumbob.formats import read

    v = np.array([[0, 0, 0], [50, 0, 0], [0, 50, 0], [0, 0, 50]], dtype=float)
    faces = [[1, 3, 2], [1, 2, 4], [1, 4, 3], [2, 3, 4]]
    path = tmp_path / "big.obj"
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in v) +
                    "".join(f"f {a} {b} {c}\n" for a, b, c in faces))
    assert any("50 × 50 × 50 m, implausible for metres" in n for n in read(str(path)).notices)
    assert not any("implausible" in n for n in read(str(path), units="mm").notices)
