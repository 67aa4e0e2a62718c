"""Ctrl-C during an engine run stops it (pymunk drops exceptions raised inside its callbacks, so SIGINT is deferred
to a safe point between steps: :mod:`throwmap.engine.pymunk.interrupt`)."""

import os
import signal
import threading

import pytest

import throwmap as tm
from throwmap.engine import Friction, ImpulseThrow, Placement, Scene, simulate
from throwmap.engine.pymunk.interrupt import check, deferred_interrupts


def test_a_sigint_in_the_block_waits_for_check():
    with pytest.raises(KeyboardInterrupt):
        with deferred_interrupts():
            os.kill(os.getpid(), signal.SIGINT)  # handled: only a flag
            done = True  # reached: nothing raised yet
            check()
    assert done
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    check()  # cleared


def test_leaving_the_block_raises_a_pending_interrupt():
    with pytest.raises(KeyboardInterrupt):
        with deferred_interrupts():
            os.kill(os.getpid(), signal.SIGINT)
    check()


def test_ctrl_c_stops_a_two_part_engine_run():
    part = tm.triangle_30_60_90()
    arm = tm.Arm(h=-0.01, length=0.5, mu=1.0)
    scene = Scene(arm, (Placement(part, x=0.15, side=1), Placement(part, x=0.35, side=0)), (tm.Wall(0.8),), 0.0,
                  Friction(part_part=0.5))
    timer = threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            for _ in range(200):  # far longer than 0.05 s
                simulate(scene, ImpulseThrow(6.0))
    finally:
        timer.cancel()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
