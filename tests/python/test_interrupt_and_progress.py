"""Ctrl-C mid-render raises KeyboardInterrupt and keeps the image so far; the next render
works; the progress callback gets the progress line's figures."""
import os
import signal
import threading
import time

import numpy as np
import pytest

from conftest import REPO


def test_ctrl_c_keeps_the_image_so_far(pathspace, small_scene):
    scene = pathspace.load(str(REPO / "scenes" / "cornell-box.pbrt"))
    started = threading.Event()

    def progress(p):
        started.set()

    def interrupt():
        started.wait(60)
        time.sleep(0.5)  # a few passes in
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt, daemon=True).start()
    begun = time.monotonic()
    # The time budget only bounds a failure: the render would otherwise take minutes.
    with pytest.raises(KeyboardInterrupt) as caught:
        scene.render(spp=100000, time=60, color="rgb", progress=progress)
    assert time.monotonic() - begun < 30
    result = caught.value.result
    assert result is scene.last_result
    assert result.interrupted and result.stats["interrupted"] and result.stats["stopped_early"]
    assert 0 < result.stats["spp_mean"] < 100000
    assert result.image.shape == (400, 400, 3) and result.image.mean() > 0

    # The next render works, and Ctrl-C is Python's again once it is over.
    small = pathspace.load(str(small_scene)).render(spp=2)
    assert not small.interrupted and small.image.any()
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(5)


def test_progress_gets_the_progress_lines_figures(pathspace):
    reports = []
    scene = pathspace.load(str(REPO / "scenes" / "cornell-box.pbrt"))
    scene.render(spp=48, color="rgb", crop=(0, 0.5, 0, 0.5), progress=reports.append)  # about a second
    assert len(reports) >= 2, "a report a few times a second, and a last one"
    assert reports[-1].final and reports[-1].fraction == 1.0 and reports[-1].eta == 0
    assert not any(p.final for p in reports[:-1]) and 0 < reports[0].fraction < 1
    assert all(p.phase == "rendering" for p in reports)
    fractions = [p.fraction for p in reports]
    assert fractions == sorted(fractions) and all(0 <= f <= 1 for f in fractions)
    assert all(p.elapsed >= 0 for p in reports)


def test_an_error_in_the_progress_callback_stops_the_render_and_is_raised(pathspace):
    scene = pathspace.load(str(REPO / "scenes" / "cornell-box.pbrt"))

    def fail(p):
        raise RuntimeError("from the callback")

    begun = time.monotonic()
    with pytest.raises(RuntimeError, match="from the callback"):
        scene.render(spp=100000, time=60, color="rgb", progress=fail)
    assert time.monotonic() - begun < 30
