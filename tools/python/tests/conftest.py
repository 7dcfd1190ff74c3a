"""Fixtures: an emulated node with its own parameter file, and tnv-fw on
the two-process rig (tnv-board-emu + tnv-fw, as tests/linux starts them)."""

import os
import subprocess
import time

import pytest

import tnv


@pytest.fixture
def node(tmp_path):
    with tnv.Node.emulated(storage=tmp_path / "params.bin") as n:
        yield n


@pytest.fixture
def daemon(tmp_path):
    """unix:PATH of a running tnv-fw (on tnv-board-emu), or a skip."""
    fw = os.environ.get("TNV_FW_EXE")
    emu = os.environ.get("TNV_BOARD_EMU_EXE")
    if not fw or not emu:
        pytest.skip("tnv-fw / tnv-board-emu not built here (TNV_FW_EXE, TNV_BOARD_EMU_EXE unset: libgpiod missing)")
    board = tmp_path / "board.sock"
    can = tmp_path / "can.sock"
    config = tmp_path / "tnv-fw.toml"
    config.write_text(
        f'[board]\ntransport = "socket"\npath = "{board}"\nreply_timeout_ms = 2000\n'
        f'[can]\ninterface = "unix:{can}"\nnode_id = 1\n'
        "[rt]\npriority = 0\nrequire = false\n"
        "[tick]\nperiod_us = 1000\n"
        f'[params]\nfile = "{tmp_path / "params.bin"}"\n')
    logs = [open(tmp_path / "emu.log", "w"), open(tmp_path / "fw.log", "w")]
    procs = [subprocess.Popen([emu, "--socket", str(board), "--scenario", "no-cut", "--once"],
                              stdout=logs[0], stderr=subprocess.STDOUT)]
    procs.append(subprocess.Popen([fw, "--config", str(config)], stdout=logs[1], stderr=subprocess.STDOUT))
    try:
        deadline = time.monotonic() + 60.0  # a deadline for a busy machine, not a speed
        while not can.exists() and time.monotonic() < deadline:
            time.sleep(0.01)
        assert can.exists(), (tmp_path / "fw.log").read_text()
        yield f"unix:{can}"
    finally:
        procs[1].terminate()
        assert procs[1].wait(timeout=10) == 0, (tmp_path / "fw.log").read_text()
        procs[0].wait(timeout=10)
        for f in logs:
            f.close()
