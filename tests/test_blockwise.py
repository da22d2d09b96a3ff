"""Block-by-block, threaded row-wise work gives the one-call answer, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plumbob.blockwise as blocks
from plumbob.blockwise import blockwise, set_workers, workers
from plumbob.stability.poses.convex import hull_mesh, own_hull
from plumbob.stability.poses.hull import build_hull3
from plumbob.stability.poses.rolling import edge_geometry


@pytest.fixture
def small_blocks(monkeypatch):
    """Blocks of 7 rows, threads from 21 rows, 3 threads: every path taken on small data."""
    monkeypatch.setattr(blocks, "BLOCK_ROWS", 7)
    monkeypatch.setattr(blocks, "MIN_THREADED_ROWS", 21)
    set_workers(3)
    yield
    set_workers(None)


def _work(x: np.ndarray):
    def rows(r: slice):
        a = x[r]
        return np.sqrt(np.abs(a[:, 0])) * a[:, 1], a[:, ::-1].copy(), a[:, 2] > 0
    return rows


@given(st.integers(0, 200), st.integers(1, 5), st.integers(0, 2**32 - 1))
@settings(max_examples=40)
def test_blocks_and_threads_change_no_bit(n, threads, seed):
    x = np.random.default_rng(seed).normal(size=(n, 3)) * 1e3
    whole = _work(x)(slice(0, n))
    set_workers(threads)
    try:
        for block in (1, 3, 64, 1000):
            blocks_answer = blockwise(n, _work(x), block=block)
            for mine, want in zip(blocks_answer, whole):
                assert mine.shape == want.shape and mine.dtype == want.dtype
                assert np.array_equal(mine, want)
    finally:
        set_workers(None)


def test_an_error_in_a_worker_thread_reaches_the_caller(small_blocks):
    def rows(r: slice):
        if r.start >= 28:
            raise ValueError(f"bad block at {r.start}")
        return (np.zeros(r.stop - r.start),)

    with pytest.raises(ValueError, match="bad block at"):
        blockwise(100, rows)


def test_the_callers_numpy_error_settings_hold_in_every_thread(small_blocks):
    x = np.zeros(100)

    def rows(r: slice):
        return (1.0 / x[r],)

    with np.errstate(divide="raise"):
        with pytest.raises(FloatingPointError):
            blockwise(100, rows)
    with np.errstate(divide="ignore"):
        assert np.all(np.isinf(blockwise(100, rows)[0]))


def test_the_thread_count_comes_from_the_environment(monkeypatch):
    set_workers(None)
    monkeypatch.setenv("PLUMBOB_THREADS", "3")
    assert workers() == 3
    set_workers(None)
    monkeypatch.setenv("PLUMBOB_THREADS", "not a number")
    assert workers() >= 1
    set_workers(1)
    assert workers() == 1
    set_workers(None)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=10, deadline=None)
def test_edge_geometry_in_threaded_blocks_is_the_one_block_answer(seed):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(40, 300)), 3))
    X = X - X.mean(axis=0) - 0.01
    h = build_hull3(X, 1e-12 * float(np.ptp(X)))
    one = edge_geometry(h, 1e-9)
    saved = blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS
    blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS = 5, 10
    set_workers(3)
    try:
        many = edge_geometry(h, 1e-9)
    finally:
        blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS = saved
        set_workers(None)
    for field in one._fields:
        assert np.array_equal(getattr(one, field), getattr(many, field)), field


@given(st.integers(0, 2**32 - 1), st.booleans())
@settings(max_examples=10, deadline=None)
def test_the_hull_and_own_hull_in_threaded_blocks_are_the_one_block_answer(seed, own):
    """The hull's planes, corner levels and far-corner heights (and an own hull's solid
    angles) come out the same, bit for bit, in blocks of 5 rows over 3 threads."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(40, 300)), 3))
    X = X / np.linalg.norm(X, axis=1)[:, None] if own else X  # on a sphere: its own hull
    X = X - X.mean(axis=0)
    eps = 1e-12 * float(np.ptp(X))
    surface = None
    if own:
        from plumbob.stability.poses.convex import hull_mesh as plain_hull

        found = plain_hull(X, eps)
        X, surface = found.points, found.tri
    one = hull_mesh(X, eps, surface)
    saved = blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS
    blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS = 5, 10
    set_workers(3)
    try:
        many = hull_mesh(X, eps, surface)
        if own:
            assert own_hull(X, surface, eps) is not None
    finally:
        blocks.BLOCK_ROWS, blocks.MIN_THREADED_ROWS = saved
        set_workers(None)
    for mine, want in zip(many, one):
        assert np.array_equal(mine, want)
