"""Frames on a Dask cluster: the independent units of a job mapped over dask.distributed.

A job is cut into *units*: one run of the `exemplar` command over a frame range whose outputs
are files. A unit may wait for other units (`after`) and may read the outputs of frames just
outside its range (`handover`): animate's hand-over between ranges, fluid's previous frame.
A unit whose outputs all exist is done, so running a plan again resumes it.

Each attempt of a unit runs the command in a fresh staging folder next to the outputs, holding
only the hand-over frames the plan names (copied from the final outputs), and moves the frames
into place (`os.replace`, atomic) when the command has succeeded. So what a unit reads never
depends on which other units happen to have finished, nor on the leftovers of an attempt that
died: a rescheduled unit writes the same bytes as the first attempt would have, and a plan
gives the same bytes on a cluster as on one machine (`run(units)` without a client).

Workers run the `exemplar` command (not the Python functions): it is the one entry point that
has every verb's frame ranges, resume and hand-over, it gives the CLI's bytes by construction,
and a unit is cancelled by killing a process (the child dies with its worker: PR_SET_PDEATHSIG).

    from dask.distributed import Client
    import exemplar.distributed as xd
    units = xd.animate_units("shot/job.json", block=100, gap=10, threads=4)
    xd.run(units, Client("tcp://scheduler:8786"))

See docs/distributed.md.
"""

from __future__ import annotations

import ctypes
import dataclasses
import json
import os
import shutil
import signal
import subprocess
import uuid
from typing import Iterable, Sequence

__all__ = ["Unit", "UnitFailed", "animate_units", "chain_units", "per_frame_units", "run",
           "run_unit", "STAGING"]

# Folder (beside the outputs) holding the staging folders of running attempts.
STAGING = ".exemplar-staging"


class UnitFailed(RuntimeError):
    """The command of a unit failed: the message holds its exit code and its last stderr line."""


@dataclasses.dataclass(frozen=True)
class Unit:
    """One run of the `exemplar` command over the frames `first`..`last` (inclusive).

    `command` is the argument list after the executable; `{first}`, `{last}` and `{output}`
    in it are replaced by the range and by the staging folder's output pattern. `output` is the
    final printf pattern of the frames (one `%d`-style field; on storage every worker sees).
    `handover` names frames outside the range whose existing outputs the command reads;
    `after` the names of the units that write them (they run first). `name` is unique in a plan.
    """
    name: str
    command: tuple[str, ...]
    output: str
    first: int
    last: int
    handover: tuple[int, ...] = ()
    after: tuple[str, ...] = ()

    def outputs(self) -> list[str]:
        """The final output files of the unit, one per frame of its range."""
        return [self.output % frame for frame in range(self.first, self.last + 1)]

    def done(self) -> bool:
        """True when every output exists (what resume skips)."""
        return all(os.path.exists(path) for path in self.outputs())


def _check_range(first: int, last: int, frames_per_unit: int) -> None:
    if last < first:
        raise ValueError(f"frames: {first}-{last} is invalid (last must be >= first)")
    if frames_per_unit < 1:
        raise ValueError(f"frames_per_unit: {frames_per_unit} is invalid (must be >= 1)")


def _command(verb: str, args: Sequence[str], range_args: Sequence[str], output_flag: str,
             threads: int | None) -> tuple[str, ...]:
    command = [verb, *map(str, args), *range_args, output_flag, "{output}", "-q"]
    if threads is not None:
        command += ["-j", str(threads)]
    return tuple(command)


def per_frame_units(verb: str, args: Sequence[str], output: str, first: int, last: int, *,
                    frames_per_unit: int = 1, threads: int | None = None) -> list[Unit]:
    """Units of a verb whose frames are independent (e.g. `noisy`: frame i depends only on
    (seed, i)): ranges of `frames_per_unit` frames, passed as `--first A --last B --output P`.
    `args` are the verb's other flags (paths absolute or relative to the workers' folder)."""
    _check_range(first, last, frames_per_unit)
    command = _command(verb, args, ["--first", "{first}", "--last", "{last}"], "--output",
                       threads)
    return [Unit(f"{verb} {a}-{min(a + frames_per_unit - 1, last)}", command, output, a,
                 min(a + frames_per_unit - 1, last))
            for a in range(first, last + 1, frames_per_unit)]


def chain_units(verb: str, args: Sequence[str], output: str, first: int, last: int, *,
                frames_per_unit: int, threads: int | None = None) -> list[Unit]:
    """Units of a verb where frame t continues from the output of frame t - 1 (`fluid`: its
    temporal term reads the previous output file): consecutive ranges, each after the previous
    one and handed its last frame. Sequential (no speed-up for one shot), but a dead worker
    loses at most one unit, and several shots' chains run side by side."""
    _check_range(first, last, frames_per_unit)
    command = _command(verb, args, ["--first", "{first}", "--last", "{last}"], "--output",
                       threads)
    units: list[Unit] = []
    for a in range(first, last + 1, frames_per_unit):
        b = min(a + frames_per_unit - 1, last)
        previous = units[-1:]
        units.append(Unit(f"{verb} {a}-{b}", command, output, a, b,
                          handover=(a - 1,) if previous else (),
                          after=tuple(u.name for u in previous)))
    return units


def animate_units(job: str, *, first: int | None = None, last: int | None = None,
                  output: str | None = None, block: int = 100, gap: int = 10,
                  chunk: int | None = None, threads: int | None = None,
                  seed: int | None = None) -> list[Unit]:
    """Units of `exemplar animate JOB.json` (docs/video.md, frame ranges and hand-over): the
    frames `first`..`last` (default: the job's) cut into blocks of `block` frames; every block
    but its last `gap` frames is solved independently (all at once on a cluster), then each gap
    joins its neighbours on both sides, handed over as keyframes. `output` defaults to the
    job's `output` (relative to the job file). Layers and `mp4` are refused (a unit writes
    frames only)."""
    with open(job, encoding="utf-8") as f:
        spec = {key.replace("_", "-"): value for key, value in json.load(f).items()}
    for refused in ("layers", "mp4"):
        if refused in spec:
            raise ValueError(f"{job}: '{refused}' is not supported by exemplar.distributed "
                             "(run the command on one machine)")
    first = spec.get("first") if first is None else first
    last = spec.get("last") if last is None else last
    if first is None or last is None:
        raise ValueError(f"{job}: give first and last (the job has no 'first'/'last')")
    if output is None:
        if "output" not in spec:
            raise ValueError(f"{job}: give output (the job has no 'output')")
        output = os.path.join(os.path.dirname(os.path.abspath(job)), spec["output"])
    _check_range(first, last, block)
    if not 1 <= gap < block:
        raise ValueError(f"gap: {gap} is invalid (must be 1..block-1 = 1..{block - 1})")
    args = [os.path.abspath(job)]
    if chunk is not None:
        args += ["--chunk", str(chunk)]
    if seed is not None:
        args += ["--seed", str(seed)]
    command = _command("animate", args, ["--frames", "{first}-{last}"], "-o", threads)

    starts = list(range(first, last + 1, block))
    blocks = []  # per block: (main unit, gap range or None)
    for a in starts:
        b = min(a + block - 1, last)
        if b == last:  # the last block has nothing after it to join
            blocks.append((Unit(f"animate {a}-{b}", command, output, a, b), None))
        else:
            blocks.append((Unit(f"animate {a}-{b - gap}", command, output, a, b - gap),
                           (b - gap + 1, b)))
    units = [main for main, _ in blocks]
    for i, (main, gap_range) in enumerate(blocks):
        if gap_range is not None:
            g0, g1 = gap_range
            following = blocks[i + 1][0]
            units.append(Unit(f"animate {g0}-{g1}", command, output, g0, g1,
                              handover=(g0 - 1, g1 + 1), after=(main.name, following.name)))
    return units


# prctl, resolved here: the child of a threaded worker must not load anything between fork and
# exec (a lock held by another thread at the fork would never be released).
_prctl = ctypes.CDLL(None, use_errno=True).prctl
_PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    # In the child, before exec: SIGKILL when the worker process dies, so a killed worker
    # leaves no command running (otherwise it would run on, orphaned, to its end).
    _prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL))


def _fill(arg: str, values: dict) -> str:
    # Plain replacement, not str.format: paths may contain braces.
    for name, value in values.items():
        arg = arg.replace("{" + name + "}", value)
    return arg


def run_unit(unit: Unit, executable: str = "exemplar", *_after: object) -> list[str]:
    """Runs one unit (on a worker or locally) unless it is done; returns its output files.

    Extra positional arguments are ignored: `run` passes the futures of `unit.after` there so
    that Dask starts the unit only when they have finished."""
    outputs = unit.outputs()
    if unit.done():
        return outputs
    if "%" in os.path.dirname(unit.output):
        raise ValueError(f"{unit.name}: output {unit.output}: the frame number must be in the "
                         "file name, not in a folder")
    final_dir = os.path.dirname(os.path.abspath(unit.output % unit.first))
    staging = os.path.join(final_dir, STAGING, f"{unit.first:08d}-{uuid.uuid4().hex}")
    for _ in range(3):  # another plan's `run` may remove the empty STAGING folder meanwhile
        try:
            os.makedirs(staging)
            break
        except FileNotFoundError:
            continue
    else:
        os.makedirs(staging)
    try:
        _attempt(unit, executable, staging, outputs)
    finally:  # a failed attempt leaves nothing; a killed one leaves its folder
        shutil.rmtree(staging, ignore_errors=True)
    return outputs


def _attempt(unit: Unit, executable: str, staging: str, outputs: list[str]) -> None:
    with open(os.path.join(staging, "attempt.json"), "w", encoding="utf-8") as f:
        json.dump({"unit": unit.name, "pid": os.getpid()}, f)
    pattern = os.path.join(staging, os.path.basename(unit.output))
    for frame in unit.handover:
        source = unit.output % frame
        if not os.path.exists(source):
            raise UnitFailed(f"{unit.name}: hand-over frame {frame} ({source}) does not exist")
        shutil.copyfile(source, pattern % frame)
    values = {"first": str(unit.first), "last": str(unit.last), "output": pattern}
    argv = [executable] + [_fill(arg, values) for arg in unit.command]
    completed = subprocess.run(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True, preexec_fn=_die_with_parent)
    if completed.returncode != 0:
        lines = completed.stderr.strip().splitlines()
        raise UnitFailed(f"{unit.name}: exemplar exited with {completed.returncode}: "
                         f"{lines[-1] if lines else '(no message)'}")
    for frame, path in zip(range(unit.first, unit.last + 1), outputs):
        os.replace(pattern % frame, path)


def _ordered(units: Iterable[Unit]) -> list[Unit]:
    """The units with every unit after those it waits for; checks names and references."""
    by_name: dict[str, Unit] = {}
    for unit in units:
        if unit.name in by_name:
            raise ValueError(f"units: the name '{unit.name}' is used twice")
        by_name[unit.name] = unit
    ordered: list[Unit] = []
    state: dict[str, int] = {}  # 1 = being visited, 2 = placed

    def visit(unit: Unit) -> None:
        if state.get(unit.name) == 2:
            return
        if state.get(unit.name) == 1:
            raise ValueError(f"units: '{unit.name}' waits for itself (a cycle)")
        state[unit.name] = 1
        for name in unit.after:
            if name not in by_name:
                raise ValueError(f"units: '{unit.name}' waits for '{name}', not in the plan")
            visit(by_name[name])
        state[unit.name] = 2
        ordered.append(unit)

    for unit in by_name.values():
        visit(unit)
    return ordered


def run(units: Iterable[Unit], client=None, *, executable: str = "exemplar",
        retries: int = 3, timeout: float | None = None) -> list[str]:
    """Runs a plan: on a dask.distributed `client`, every unit as a task as soon as the units it
    waits for are done (a unit that fails or whose worker dies is retried up to `retries`
    times); without a client, one unit after the other in this process (the single-machine
    run: the same bytes). Units already done are skipped. Returns every output file, in plan
    order; raises the first unit's error (UnitFailed) once its retries are spent.

    `executable` is the `exemplar` command as the workers see it (on their PATH by default).
    `timeout` (seconds) bounds the wait for the whole plan on a cluster."""
    ordered = _ordered(units)
    try:
        if client is None:
            for unit in ordered:
                run_unit(unit, executable)
        else:
            _run_on(client, ordered, executable, retries, timeout)
    finally:
        # An empty staging folder is removed; a dead attempt's stays (docs/distributed.md).
        for folder in {os.path.dirname(os.path.abspath(unit.output % unit.first))
                       for unit in ordered}:
            try:
                os.rmdir(os.path.join(folder, STAGING))
            except OSError:
                pass
    return [path for unit in ordered for path in unit.outputs()]


def _run_on(client, ordered: list[Unit], executable: str, retries: int,
            timeout: float | None) -> None:
    futures = {}
    for unit in ordered:
        if unit.done():  # resume: not even a task
            continue
        waits = [futures[name] for name in unit.after if name in futures]
        futures[unit.name] = client.submit(run_unit, unit, executable, *waits,
                                           key=f"exemplar-{unit.name}-{uuid.uuid4().hex}",
                                           pure=False, retries=retries)
    _gather(client, list(futures.values()), timeout)


def _gather(client, futures, timeout):
    # Waits for every unit, then raises the first error (the plan's outputs are what counts).
    from distributed import wait

    try:
        wait(futures, timeout=timeout, return_when="ALL_COMPLETED")
    except TimeoutError:
        client.cancel(futures)
        raise TimeoutError(f"the units did not finish within {timeout} s") from None
    client.gather(futures, errors="raise")
