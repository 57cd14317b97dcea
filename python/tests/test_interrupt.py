"""Ctrl-C stops a long paving between levels with a valid, coarser result."""

import os
import signal
import threading
import time

import pytest

import detach


@pytest.fixture(autouse=True)
def python_handles_sigint():
    """Python's own Ctrl-C handler, as in an interactive session: a process
    started in the background of a shell inherits SIGINT ignored."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def sigint_after(seconds):
    t = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    t.start()
    return t


def test_ctrl_c_returns_the_partial_paving(tmp_path):
    scene = detach.Scene.load("painleve-rod", mu="1.5")
    # Far too fine to finish in a test: only an interruption ends it soon.
    start = time.monotonic()
    timer = sigint_after(0.3)
    with pytest.raises(detach.Interrupted) as e:
        scene.pave(eps=2.0**-30, max_boxes=20_000_000)
    timer.join()
    assert time.monotonic() - start < 60
    partial = e.value.paving
    assert isinstance(e.value, KeyboardInterrupt)
    assert partial.stop == "interrupted" and not partial.complete
    assert len(partial) > 0
    # Valid: its bounds enclose those of a finished paving, and its proof
    # is checked VALID.
    fine = scene.pave(eps=1 / 256)
    for name, a in partial.areas.items():
        b = fine.areas[name]
        assert a.inner <= b.outer and b.inner <= a.outer, name
    path = tmp_path / "partial.json"
    partial.save_proof(path)
    assert detach.verify(path).valid


def test_other_threads_run_while_paving():
    """The GIL is released: a Python thread makes progress meanwhile."""
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    scene = detach.Scene.load("ice-disc")
    t.start()
    try:
        before = len(ticks)
        p = scene.pave(eps=1 / 65536)
        during = len(ticks) - before
    finally:
        stop.set()
        t.join()
    assert p.elapsed > 0.05, "the paving is too short to tell"
    assert during >= 10


def test_ctrl_c_returns_the_partial_atlas(tmp_path):
    scene = detach.Scene.load("viscous-disc")
    start = time.monotonic()
    timer = sigint_after(0.3)
    with pytest.raises(detach.Interrupted) as e:
        # Far too fine to finish in a test: only an interruption ends it soon.
        scene.param_atlas("b=0:0.9", y="mu=0.25:2", eps=2.0**-14, max_boxes=10_000_000)
    timer.join()
    assert time.monotonic() - start < 60
    partial = e.value.atlas
    assert e.value.result is partial and not partial.complete and len(partial) > 0
    path = tmp_path / "partial-atlas.json"
    partial.save_proof(path)
    assert detach.verify(path).valid


def test_progress_is_called_per_level_and_its_exception_stops_the_run():
    scene = detach.Scene.load("painleve-rod")
    calls = []
    paving = scene.pave(eps=1 / 64, progress=lambda *a: calls.append(a))
    levels = [c[0] for c in calls]
    # One call per level, in order, the leaves so far never more than the end's.
    assert len(calls) >= 6 and levels == sorted(levels) and len(set(levels)) == len(levels)
    assert all(0 <= leaves <= len(paving) for _, _, leaves in calls)

    class Enough(Exception):
        pass

    def stop_at_level_3(level, open_boxes, leaves):
        if level >= 3:
            raise Enough()

    with pytest.raises(Enough):
        scene.pave(eps=1 / 1024, progress=stop_at_level_3)
    with pytest.raises(detach.DetachError, match="progress must be a callable"):
        scene.pave(progress="yes")
    seen = []
    scene.param_atlas("mu=1:2", eps=1 / 64, progress=lambda *a: seen.append(a))
    assert seen and [s[0] for s in seen] == sorted(s[0] for s in seen)
