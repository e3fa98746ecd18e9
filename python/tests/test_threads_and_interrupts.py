"""The GIL is released while pbrkit works (two renders in two threads overlap in time),
Ctrl-C raises KeyboardInterrupt in bounded time, and a progress callable can stop a render
early (which then returns what it has)."""

import _thread
import threading
import time

import numpy as np
import pytest

import pbrkit


def test_two_threads_render_at_the_same_time():
    scene = pbrkit.load("spheres")
    kwargs = dict(spp=24, width=64, height=64, threads=1, noise_threshold=0)
    t0 = time.perf_counter()
    pbrkit.render(scene, **kwargs)
    one = time.perf_counter() - t0

    spans, results = {}, {}

    def work(name):
        start = time.perf_counter()
        results[name] = pbrkit.render(scene, **kwargs)
        spans[name] = (start, time.perf_counter())

    threads = [threading.Thread(target=work, args=(n,)) for n in ("a", "b")]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    both = time.perf_counter() - t0
    (a0, a1), (b0, b1) = spans["a"], spans["b"]
    overlap = min(a1, b1) - max(a0, b0)
    print(f"one render {one:.2f} s, two in two threads {both:.2f} s, overlap {overlap:.2f} s")
    # With the GIL held, the second render could only start once the first had ended
    # (overlap <= 0). Released, both run for most of each other's time.
    assert overlap > 0.5 * min(a1 - a0, b1 - b0)
    assert np.array_equal(results["a"], results["b"])


def test_ctrl_c_raises_keyboard_interrupt_promptly():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        # About a minute of work at the machine's speed: the interrupt must cut it short.
        pbrkit.render("spheres", spp=1 << 16, width=128, height=128, noise_threshold=0)
    elapsed = time.perf_counter() - t0
    timer.cancel()
    assert elapsed < 10.0, f"KeyboardInterrupt after {elapsed:.1f} s"


def test_progress_callable_sees_progress_and_can_stop_early():
    seen = []

    def progress(fraction, detail):
        seen.append(fraction)
        return len(seen) < 3  # stop after a few reports

    t0 = time.perf_counter()
    image = pbrkit.render("spheres", spp=1 << 16, width=64, height=64, noise_threshold=0,
                          progress=progress)
    assert time.perf_counter() - t0 < 20.0
    assert len(seen) >= 3 and all(0.0 <= f <= 1.0 for f in seen)
    assert seen[-1] < 0.5  # stopped long before the end
    assert image.shape == (64, 64, 3) and np.all(np.isfinite(image)) and image.mean() > 0


def test_an_exception_in_the_progress_callable_propagates():
    def progress(fraction, detail):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        pbrkit.render("spheres", spp=1 << 16, width=64, height=64, noise_threshold=0,
                      progress=progress)
