"""Running a call: progress callbacks, cancellation (callback, CancelToken, Ctrl-C) and the GIL
released while the library works."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import exemplar
from conftest import gradient, pattern


def test_progress_reports_increasing_fractions(large):
    style, source, target = large
    events = []
    exemplar.stylize(style, [(source, target)], progress=events.append)
    assert len(events) > 3
    fractions = [event.fraction for event in events]
    assert fractions == sorted(fractions)
    assert 0.0 <= fractions[0] and fractions[-1] == pytest.approx(1.0)
    assert all(isinstance(event, exemplar.Progress) for event in events)
    assert {event.levels for event in events} == {events[-1].levels}
    assert all(event.stage for event in events)


def test_a_callback_returning_false_cancels(pair):
    style, source, target = pair
    calls = []

    def stop(event):
        calls.append(event.fraction)
        return False

    with pytest.raises(exemplar.Cancelled, match="^cancelled$"):
        exemplar.stylize(style, [(source, target)], progress=stop)
    assert len(calls) == 1


def test_a_callback_that_raises_cancels_and_its_exception_propagates(pair):
    style, source, target = pair

    def fail(event):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        exemplar.stylize(style, [(source, target)], progress=fail)


def test_a_cancel_token_set_from_another_thread_cancels(large):
    style, source, target = large
    token = exemplar.CancelToken()
    started = threading.Event()
    setter = threading.Thread(target=lambda: (started.wait(), token.cancel()))
    setter.start()
    with pytest.raises(exemplar.Cancelled):
        exemplar.stylize(style, [(source, target)], threads=1, cancel=token,
                         progress=lambda event: started.set())
    setter.join()
    assert token.cancelled
    # A set token stays set: the next call using it stops at once.
    with pytest.raises(exemplar.Cancelled):
        exemplar.stylize(style, [(source, target)], cancel=token)


def test_ctrl_c_cancels_and_raises_keyboard_interrupt(large):
    style, source, target = large
    started = threading.Event()

    def interrupt():
        started.wait()
        os.kill(os.getpid(), signal.SIGINT)

    killer = threading.Thread(target=interrupt)
    killer.start()
    begin = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        exemplar.stylize(style, [(source, target)], threads=1,
                         progress=lambda event: started.set())
    killer.join()
    full = time.monotonic()
    exemplar.stylize(style, [(source, target)], threads=1)
    # Stopped early, not after the whole run.
    assert full - begin < (time.monotonic() - full)


def test_the_gil_is_released_while_the_library_works():
    # Larger than `large`, and the best quality: about half a second on one thread.
    style, source, target = pattern(160, 192, 3, 0.5), gradient(160, 192), gradient(200, 224)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.002)

    ticker = threading.Thread(target=tick)
    ticker.start()
    begin = time.monotonic()
    exemplar.stylize(style, [(source, target)], threads=1, quality="best")
    end = time.monotonic()
    done.set()
    ticker.join()
    during = [t for t in ticks if begin <= t <= end]
    gaps = np.diff([begin] + during + [end])
    # Holding the GIL would leave one gap as long as the call.
    assert end - begin > 0.1, "the run is too short to tell"
    assert len(during) >= 5
    assert gaps.max() < (end - begin) / 2
