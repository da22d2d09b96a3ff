import os

import numpy as np
import pytest
from hypothesis import settings

# Property tests: 40 examples each, no deadline (a loaded 2-core machine). In CI (CI=true,
# as .ci/run sets it) they are derandomised: the examples follow from each test alone, so a
# red run is the same red run when repeated, and no example database is kept.
settings.register_profile("dev", max_examples=40, deadline=None)
settings.register_profile("ci", max_examples=40, deadline=None, derandomize=True,
                          database=None, print_blob=True)
settings.load_profile("ci" if os.environ.get("CI", "").lower() in ("true", "1") else "dev")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHAPES = os.path.join(ROOT, "shapes")


@pytest.fixture
def shapes_dir() -> str:
    return SHAPES


def star_polygon(rng: np.random.Generator, n: int, centre=(0.0, 0.0)) -> np.ndarray:
    """A random simple (star-shaped) polygon, counter-clockwise."""
    # Spread angles (gaps below π for n ≥ 4) keep the origin inside: simple and CCW.
    angles = 2 * np.pi * (np.arange(n) + rng.uniform(0, 0.8, n)) / n
    radii = rng.uniform(0.3, 1.0, n)
    return np.stack((radii * np.cos(angles), radii * np.sin(angles)), axis=1) + centre


def rel(a, b, scale: float | None = None) -> float:
    """Largest difference between a and b relative to ``scale`` (default: b's largest entry).

    Pass the body's size as ``scale`` for centres near zero, where a relative
    comparison entry by entry would compare round-off with round-off.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    scale = np.max(np.abs(b)) if scale is None else scale
    return float(np.max(np.abs(a - b)) / max(scale, 1e-300))
