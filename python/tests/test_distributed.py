"""exemplar.distributed: units of animate and fluid on a LocalCluster of 2 worker processes,
one of them killed mid-unit; the frames must be those of the same plan run on one machine."""

import json
import os
import pathlib
import signal
import subprocess
import threading
import time

import distributed  # Debian's python3-distributed (scripts/install-deps.sh)
import numpy as np
import pytest

import exemplar
import exemplar.distributed as xd
from conftest import gradient, pattern

# Bounded but generous: the machine running the tests is shared and busy.
PLAN_TIMEOUT_S = 240


def make_clip(folder: pathlib.Path) -> pathlib.Path:
    """8 frames of 48x32 (a pattern sliding 1 px per frame) and an animate job over them."""
    (folder / "frames").mkdir(parents=True)
    strip = pattern(32, 64, 3, 0.3)
    for i in range(8):
        exemplar.save_image(np.ascontiguousarray(strip[:, i:i + 48]),
                            str(folder / f"frames/{i:04d}.png"))
    exemplar.save_image(gradient(40, 44, 3), str(folder / "style_in.png"))
    exemplar.save_image(pattern(40, 44, 3, 1.0), str(folder / "style_out.png"))
    job = {"frames": "frames/%04d.png", "first": 0, "last": 7, "flows": "estimate",
           "style": {"input": "style_in.png", "output": "style_out.png"}, "levels": 2,
           "output": "out/%04d.png"}
    (folder / "job.json").write_text(json.dumps(job))
    return folder / "job.json"


def frame_bytes(folder: pathlib.Path) -> dict:
    return {p.name: p.read_bytes() for p in sorted((folder / "out").glob("*.png"))}


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address=None,
                                       silence_logs=50)
    client = distributed.Client(cluster, timeout=120)
    client.wait_for_workers(2, timeout=120)
    yield client
    client.close()
    cluster.close()


def test_animate_plan_blocks_then_gaps(tmp_path):
    job = make_clip(tmp_path)
    units = xd.animate_units(str(job), block=4, gap=1, threads=1)
    assert [(u.first, u.last, u.handover, u.after) for u in units] == [
        (0, 2, (), ()), (4, 7, (), ()), (3, 3, (2, 4), ("animate 0-2", "animate 4-7"))]
    assert units[0].output == str(tmp_path / "out/%04d.png")
    assert units[0].outputs() == [str(tmp_path / f"out/{i:04d}.png") for i in range(3)]
    with pytest.raises(ValueError, match="gap: 4 is invalid"):
        xd.animate_units(str(job), block=4, gap=4)
    (tmp_path / "layered.json").write_text(json.dumps({"layers": [], "first": 0, "last": 1}))
    with pytest.raises(ValueError, match="'layers' is not supported"):
        xd.animate_units(str(tmp_path / "layered.json"))


def test_chain_and_per_frame_plans():
    chain = xd.chain_units("fluid", ["--exemplar", "ex.png"], "out/%04d.png", 0, 6,
                           frames_per_unit=3)
    assert [(u.first, u.last, u.handover, u.after) for u in chain] == [
        (0, 2, (), ()), (3, 5, (2,), ("fluid 0-2",)), (6, 6, (5,), ("fluid 3-5",))]
    assert chain[0].command == ("fluid", "--exemplar", "ex.png", "--first", "{first}",
                                "--last", "{last}", "--output", "{output}", "-q")
    frames = xd.per_frame_units("noisy", ["--seed", "3"], "n/%04d.png", 5, 7)
    assert [(u.first, u.last, u.after) for u in frames] == [(5, 5, ()), (6, 6, ()), (7, 7, ())]
    with pytest.raises(ValueError, match="waits for 'nowhere'"):
        xd.run([xd.Unit("a", ("x",), "o/%d.png", 0, 0, after=("nowhere",))])


def test_a_one_block_plan_is_one_animate_run(cli, tmp_path):
    job = make_clip(tmp_path)
    subprocess.run([cli, "animate", str(job), "-q", "-j", "1", "-o",
                    str(tmp_path / "one/%04d.png")], check=True)
    units = xd.animate_units(str(job), block=8, gap=1, threads=1)
    assert [(u.first, u.last) for u in units] == [(0, 7)]
    xd.run(units, executable=cli)
    for i in range(8):
        assert ((tmp_path / f"out/{i:04d}.png").read_bytes() ==
                (tmp_path / f"one/{i:04d}.png").read_bytes())


def commands_writing_into(folder: pathlib.Path) -> list:
    """Pids of the processes whose command line names `folder`."""
    pids = []
    for proc in pathlib.Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and str(folder).encode() in (proc / "cmdline").read_bytes():
                pids.append(int(proc.name))
        except OSError:  # ended meanwhile
            pass
    return pids


def test_a_failing_unit_raises_the_commands_message(cli, tmp_path):
    unit = xd.Unit("bad", ("animate", str(tmp_path / "missing.json"), "--frames",
                           "{first}-{last}", "-o", "{output}"), str(tmp_path / "o/%04d.png"), 0, 1)
    with pytest.raises(xd.UnitFailed, match=r"bad: exemplar exited with 1: .*missing\.json"):
        xd.run([unit], executable=cli)
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


def alive(pid: int) -> bool:
    """True while the process exists and is not a zombie."""
    try:
        return pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def kill_one_attempt(staging: pathlib.Path, worker_pids: set, killed: list, stop):
    """Kills the worker running the first unit whose command is seen running in a staging
    folder under `staging` (its attempt.json names the worker's pid). Records (unit, worker pid,
    whether the command was gone 0.5 s after the worker: the parent-death signal is immediate,
    a unit runs for about a second) when the attempt was still unfinished once the worker was
    dead (its staging folder still there); else tries the next attempt."""
    tried = set()
    while not stop.is_set() and not killed:
        for attempt in staging.glob("*/attempt.json") if staging.is_dir() else []:
            if attempt in tried:
                continue
            try:
                info = json.loads(attempt.read_text())
            except (OSError, ValueError):  # being written: read it next time round
                continue
            commands = commands_writing_into(attempt.parent)
            if info["pid"] not in worker_pids or not commands:
                continue  # not a worker of this cluster, or its command is not running yet
            tried.add(attempt)
            os.kill(info["pid"], signal.SIGKILL)
            while alive(info["pid"]) and not stop.is_set():
                time.sleep(0.01)
            deadline = time.monotonic() + 0.5
            while commands_writing_into(attempt.parent) and time.monotonic() < deadline:
                time.sleep(0.01)
            if attempt.parent.is_dir():
                killed.append((info["unit"], info["pid"],
                               not commands_writing_into(attempt.parent)))
                return
        time.sleep(0.01)


def test_a_killed_worker_changes_no_byte(cli, client, tmp_path):
    single, cluster = tmp_path / "single", tmp_path / "cluster"
    for folder in (single, cluster):
        make_clip(folder)
    plan = lambda folder: xd.animate_units(str(folder / "job.json"), block=4, gap=1, threads=1)
    xd.run(plan(single), executable=cli)
    expected = frame_bytes(single)
    assert not (single / "out" / xd.STAGING).exists()  # removed once empty
    assert sorted(expected) == [f"{i:04d}.png" for i in range(8)]

    worker_pids = set(client.run(os.getpid).values())
    killed, stop = [], threading.Event()
    killer = threading.Thread(target=kill_one_attempt,
                              args=(cluster / "out" / xd.STAGING, worker_pids, killed, stop))
    killer.start()
    try:
        outputs = xd.run(plan(cluster), client, executable=cli, timeout=PLAN_TIMEOUT_S)
    finally:
        stop.set()
        killer.join()
    assert killed, "no unit was running when a worker could be killed"
    assert outputs == [str(cluster / f"out/{i:04d}.png") for i in (0, 1, 2, 4, 5, 6, 7, 3)]
    assert frame_bytes(cluster) == expected
    assert [p.name for p in (cluster / "out").iterdir() if not p.name.endswith(".png")] == [
        xd.STAGING]  # holding the dead attempt's folder only
    assert list((cluster / "out" / xd.STAGING).iterdir())
    unit, worker, command_died_with_worker = killed[0]
    assert command_died_with_worker, f"{unit}: the command outlived its killed worker"
    client.wait_for_workers(2, timeout=120)  # the nanny restarted it
    assert worker not in set(client.run(os.getpid).values())


def test_resume_redoes_only_missing_units(cli, client, tmp_path):
    job = make_clip(tmp_path)
    units = xd.animate_units(str(job), block=4, gap=1, threads=1)
    xd.run(units, client, executable=cli, timeout=PLAN_TIMEOUT_S)
    expected = frame_bytes(tmp_path)
    out = tmp_path / "out"
    stamps = {p.name: p.stat().st_mtime_ns for p in out.glob("*.png")}
    (out / "0005.png").unlink()  # unit 4-7 is no longer done; 0-2 and the gap 3 are
    time.sleep(0.05)
    xd.run(units, client, executable=cli, timeout=PLAN_TIMEOUT_S)
    assert frame_bytes(tmp_path) == expected
    for name in ("0000.png", "0001.png", "0002.png", "0003.png"):
        assert (out / name).stat().st_mtime_ns == stamps[name]
    assert (out / "0006.png").stat().st_mtime_ns != stamps["0006.png"]


def test_fluid_in_chained_units_is_one_run(cli, client, tmp_path):
    subprocess.run([cli, "fluid", "simulate", "--scene", "plume", "--width", "48", "--height",
                    "32", "--frames", "6", "-o", str(tmp_path / "sim"), "-q"], check=True)
    exemplar.save_image(np.concatenate([pattern(24, 24, 3, 0.7), gradient(24, 24)], axis=-1),
                        str(tmp_path / "fire.png"))
    args = ["--exemplar", str(tmp_path / "fire.png"),
            "--alpha", str(tmp_path / "sim/alpha/%04d.png"),
            "--motion", str(tmp_path / "sim/motion/%04d.flo"), "-j", "1"]
    subprocess.run([cli, "fluid", *args, "--first", "0", "--last", "5", "--output",
                    str(tmp_path / "one/%04d.png"), "-q"], check=True)
    units = xd.chain_units("fluid", args, str(tmp_path / "chain/%04d.png"), 0, 5,
                           frames_per_unit=2)
    xd.run(units, client, executable=cli, timeout=PLAN_TIMEOUT_S)
    for i in range(6):
        assert ((tmp_path / f"chain/{i:04d}.png").read_bytes() ==
                (tmp_path / f"one/{i:04d}.png").read_bytes())


def test_noisy_frames_one_unit_each_are_one_run(cli, client, tmp_path):
    # Color Me Noisy: frame i depends only on (seed, i), so every frame is its own unit.
    verbs = subprocess.run([cli, "--help"], capture_output=True, text=True, check=True).stdout
    if "\n  noisy " not in verbs:  # before the merge of the noisy branch
        pytest.skip("this exemplar has no `noisy` verb")
    make_clip(tmp_path)
    args = ["--exemplar", str(tmp_path / "style_out.png"),
            "--frames", str(tmp_path / "frames/%04d.png"), "--noise", "2", "--seed", "3"]
    subprocess.run([cli, "noisy", *args, "--first", "0", "--last", "5", "-o",
                    str(tmp_path / "one/%04d.png"), "-q", "-j", "1"], check=True)
    units = xd.per_frame_units("noisy", args, str(tmp_path / "each/%04d.png"), 0, 5, threads=1)
    assert len(units) == 6
    xd.run(units, client, executable=cli, timeout=PLAN_TIMEOUT_S)
    for i in range(6):
        assert ((tmp_path / f"each/{i:04d}.png").read_bytes() ==
                (tmp_path / f"one/{i:04d}.png").read_bytes())
