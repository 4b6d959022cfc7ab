"""app.jobs.signals: on SIGINT and SIGTERM the jobs hear of the stop first (the callback, run
in their event loop), then the handler that was there before (uvicorn's) runs as it would have;
`restore` puts that handler back. Off the main thread nothing is installed.

Every signal here is raised (`signal.raise_signal`) with a handler of the test's own in place,
never the default one, so nothing can stop the test process; `own_handlers` puts the session's
handlers back whatever happens."""

from __future__ import annotations

import asyncio
import signal
import threading
from collections.abc import Iterator
from typing import Any

import pytest

from app.jobs.signals import on_shutdown_signals

SIGNALS = [signal.SIGINT, signal.SIGTERM]
IDS = ["SIGINT", "SIGTERM"]


class Recorder:
    """A handler that records the signals it gets."""

    def __init__(self) -> None:
        self.received: list[int] = []

    def __call__(self, signum: int, frame: Any) -> None:
        self.received.append(signum)


@pytest.fixture
def own_handlers() -> Iterator[Recorder]:
    """A recording handler on SIGINT and SIGTERM for the test, the previous ones after it."""
    saved = {signum: signal.getsignal(signum) for signum in SIGNALS}
    recorder = Recorder()
    for signum in SIGNALS:
        signal.signal(signum, recorder)
    try:
        yield recorder
    finally:
        for signum, handler in saved.items():
            signal.signal(signum, handler)


@pytest.fixture
def loop() -> Iterator[asyncio.AbstractEventLoop]:
    loop = asyncio.new_event_loop()
    try:
        yield loop
    finally:
        loop.close()


def _turn(loop: asyncio.AbstractEventLoop) -> None:
    """Run what is scheduled on `loop` (the callback the handler scheduled, if any)."""
    loop.run_until_complete(asyncio.sleep(0))


@pytest.mark.parametrize("signum", SIGNALS, ids=IDS)
def test_a_shutdown_signal_calls_back_in_the_loop_then_the_previous_handler(
    own_handlers: Recorder, loop: asyncio.AbstractEventLoop, signum: int
) -> None:
    called: list[str] = []
    restore = on_shutdown_signals(loop, lambda: called.append("stopping"))
    signal.raise_signal(signum)
    assert own_handlers.received == [signum]  # chained at once, in the handler
    assert called == []  # the callback runs in the loop, not in the handler
    _turn(loop)
    assert called == ["stopping"]
    restore()


@pytest.mark.parametrize("signum", SIGNALS, ids=IDS)
def test_restore_puts_the_previous_handler_back(
    own_handlers: Recorder, loop: asyncio.AbstractEventLoop, signum: int
) -> None:
    called: list[str] = []
    restore = on_shutdown_signals(loop, lambda: called.append("stopping"))
    assert signal.getsignal(signum) is not own_handlers
    restore()
    restored: object = signal.getsignal(signum)
    assert restored is own_handlers
    signal.raise_signal(signum)
    _turn(loop)
    assert own_handlers.received == [signum] and called == []


def test_restore_leaves_a_handler_installed_since_in_place(
    own_handlers: Recorder, loop: asyncio.AbstractEventLoop
) -> None:
    restore = on_shutdown_signals(loop, lambda: None)
    later = Recorder()
    signal.signal(signal.SIGTERM, later)
    restore()
    assert signal.getsignal(signal.SIGTERM) is later
    assert signal.getsignal(signal.SIGINT) is own_handlers


def test_a_signal_after_the_loop_closed_still_reaches_the_previous_handler(
    own_handlers: Recorder,
) -> None:
    closed = asyncio.new_event_loop()
    restore = on_shutdown_signals(closed, lambda: None)
    closed.close()
    try:
        signal.raise_signal(signal.SIGTERM)  # the loop cannot take the callback: no error
    finally:
        restore()
    assert own_handlers.received == [signal.SIGTERM]


def test_off_the_main_thread_nothing_is_installed(
    own_handlers: Recorder, loop: asyncio.AbstractEventLoop
) -> None:
    restores: list[Any] = []
    thread = threading.Thread(target=lambda: restores.append(on_shutdown_signals(loop, print)))
    thread.start()
    thread.join(10)
    assert len(restores) == 1
    assert all(signal.getsignal(signum) is own_handlers for signum in SIGNALS)
    restores[0]()  # and undoing it does nothing
    assert all(signal.getsignal(signum) is own_handlers for signum in SIGNALS)
