"""render(progress=True or "tqdm"): a tqdm bar when tqdm is installed, the command line's bar
when it is not (tqdm is not a dependency). A fake tqdm module in sys.modules records the bar."""
import sys
import time
import types

import pytest


class FakeBar:
    bars = []

    def __init__(self, total, desc, unit, bar_format):
        self.total, self.desc, self.n, self.updates, self.closed = total, desc, 0, [], False
        FakeBar.bars.append(self)

    def update(self, k):
        assert not self.closed
        self.n += k
        self.updates.append(k)

    def close(self):
        self.closed = True


@pytest.fixture
def fake_tqdm(monkeypatch):
    module = types.ModuleType("tqdm")
    module.tqdm = FakeBar
    FakeBar.bars = []
    monkeypatch.setitem(sys.modules, "tqdm", module)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # import tqdm.auto fails: the plain bar
    return FakeBar


@pytest.fixture
def no_tqdm(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import tqdm raises ImportError
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)


@pytest.mark.parametrize("progress", [True, "tqdm"])
def test_a_tqdm_bar_counts_to_100_and_is_closed(pathspace, small_scene, fake_tqdm, capfd, progress):
    pathspace.load(str(small_scene)).render(spp=64, progress=progress)
    assert len(fake_tqdm.bars) == 1
    bar = fake_tqdm.bars[0]
    assert bar.desc == "rendering" and bar.total == 100 and bar.n == 100 and bar.closed
    assert all(k > 0 for k in bar.updates)
    assert "rendering" not in capfd.readouterr().err  # not the command line's bar as well


def test_the_bar_is_closed_when_the_render_stops(pathspace, small_scene, fake_tqdm, monkeypatch):
    # The bar's own error stops the render before its final report: the bar is closed all the same.
    def fail(bar, k):
        raise RuntimeError("from the bar")

    monkeypatch.setattr(fake_tqdm, "update", fail)
    begun = time.monotonic()
    with pytest.raises(RuntimeError, match="from the bar"):
        pathspace.load(str(small_scene)).render(spp=100000, time=60, progress=True)  # seconds
    assert time.monotonic() - begun < 30
    assert len(fake_tqdm.bars) == 1 and fake_tqdm.bars[0].closed


def test_without_tqdm_the_command_lines_bar(pathspace, small_scene, no_tqdm, capfd):
    scene = pathspace.load(str(small_scene))
    result = scene.render(spp=16, progress=True)
    assert result.image.any() and "rendering" in capfd.readouterr().err
    with pytest.warns(RuntimeWarning, match="tqdm is not installed"):
        scene.render(spp=16, progress="tqdm")
    assert "rendering" in capfd.readouterr().err


def test_bad_progress_values(pathspace, small_scene):
    scene = pathspace.load(str(small_scene))
    with pytest.raises(ValueError, match='got "bar"'):
        scene.render(spp=1, progress="bar")
    with pytest.raises(ValueError, match="or a callable"):
        scene.render(spp=1, progress=3)
