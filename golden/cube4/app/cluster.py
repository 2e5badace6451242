"""Bricks on several boards: a Dask distributed executor for ``cube4.bricks``.

``DaskExecutor`` runs brick tasks on a ``dask.distributed`` cluster: a ``LocalCluster``
of ``workers`` processes (one thread each), or the scheduler at ``scheduler``
(``tcp://HOST:PORT``) of a real cluster whose workers have this package installed. Each
task carries its brick's voxels, view, tables and window, so the scheduler can send it
again: a worker that dies in mid-frame (killed, out of memory, its machine gone) costs
that brick a retry on another worker, not the frame (Dask reschedules the tasks of a lost
worker; ``RETRIES`` more runs are allowed for a task that raises). The partial base
planes come back as they finish (a progress callback counts the bricks done) and are
composited in this process, front to back, as a tree of ``over``.

This module is the host side of the renderer; the golden model never imports it, and
``dask`` is imported only when an executor starts.
"""

from __future__ import annotations

import contextlib
import ipaddress
import logging
import os
import re
import time
import uuid
import warnings
from collections.abc import Sequence
from pathlib import Path

from ..bricks import BrickResult, BrickTask, run_task
from ..errors import UserError
from ..progress import Progress, counted
from ..values import shown

RETRIES = 2              # more runs of a task that raised (a worker's death is counted by Dask itself)
CONNECT_TIMEOUT_S = 20   # reaching the scheduler
MAX_WORKERS = 256
NO_TRIM = "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"
_SCHEDULER = re.compile(r"^tcp://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9]([A-Za-z0-9.-]{0,252}))(?::([0-9]{1,5}))?$")


def check_scheduler(address: str) -> str:
    """tcp://HOST[:PORT] with HOST a name, an IPv4 address or a bracketed IPv6 address and
    PORT in 1..65535 (Dask's default 8786 when left out); other protocols are refused."""
    bad = f"--scheduler must be a Dask scheduler address tcp://HOST:PORT, got {shown(address, 80)}"
    m = _SCHEDULER.match(address) if isinstance(address, str) else None
    if not m:
        if isinstance(address, str) and re.match(r"^[a-z]+://", address) and not address.startswith("tcp://"):
            raise UserError(f"{bad} (only tcp:// is supported)")
        raise UserError(bad)
    host, port = m[1], m[3]
    if host.startswith("["):
        try:
            ipaddress.IPv6Address(host[1:-1])
        except ValueError:
            raise UserError(f"{bad} ({host} is not an IPv6 address)") from None
    elif any(not 1 <= len(label) <= 63 or label.startswith("-") or label.endswith("-")
             for label in host.rstrip(".").split(".")):
        raise UserError(f"{bad} ({host!r} is not a host name)")
    if port is not None and not 1 <= int(port) <= 65535:
        raise UserError(f"{bad} (the port must be in 1..65535)")
    return address


def _run(task: BrickTask, journal: str | None, hold: str | None) -> BrickResult:
    """One brick on a worker. ``journal``: a folder where each run leaves
    ``<label>.<pid>.start`` and ``.done`` (which runs were interrupted); ``hold``: a file
    whose presence makes the run wait before rendering (fault-injection hook: a test
    kills the worker while it waits)."""
    name = task.label.replace(" ", "_").replace(",", "-")
    pid = os.getpid()
    if journal:
        Path(journal, f"{name}.{pid}.start").touch()
    if hold:
        t_end = time.monotonic() + 300.0
        while os.path.exists(hold) and time.monotonic() < t_end:
            time.sleep(0.02)
    res = run_task(task)
    res.worker = f"{os.uname().nodename}:{pid}"
    if journal:
        Path(journal, f"{name}.{pid}.done").touch()
    return res


class DaskExecutor:
    """Brick tasks on a Dask cluster (a context manager: starts or connects, then closes)."""

    name = "dask"

    def __init__(self, workers: int | None = None, scheduler: str | None = None, *, timeout: float | None = None,
                 journal: str | None = None, hold: str | None = None, quiet: bool = True):
        if (workers is None) == (scheduler is None):
            raise ValueError("give workers (a LocalCluster) or scheduler (an address), one of them")
        if workers is not None and not 1 <= workers <= MAX_WORKERS:
            raise UserError(f"--workers must be in 1..{MAX_WORKERS}, got {workers}")
        self.n_workers = workers
        self.scheduler = check_scheduler(scheduler) if scheduler is not None else None
        self.timeout = timeout
        self.journal, self.hold = journal, hold
        self.quiet = quiet
        self.cluster = self.client = None
        self.start_s = 0.0
        self._retries = 0
        self._stack = contextlib.ExitStack()

    # --- lifetime
    def __enter__(self):
        t0 = time.perf_counter()
        try:
            import dask
            from distributed import Client, LocalCluster
        except ImportError:
            raise UserError("--workers and --scheduler need dask.distributed (pip install distributed)") from None
        # a brick that fails and is run again is no news; a frame that fails is one line from run()
        level = logging.CRITICAL if self.quiet else logging.WARNING
        for name in ("distributed", "tornado"):
            logging.getLogger(name).setLevel(level)
        # Dask's nannies start workers with MALLOC_TRIM_THRESHOLD_=65536, which fixes glibc's mmap
        # threshold and makes every slice-sized array a fresh mmap: the model ran 3-4x slower
        # (measured). Local workers start without it; remote ones are started by their owner.
        self._stack.enter_context(dask.config.set({NO_TRIM: None}))
        try:
            if self.scheduler is None:
                self.cluster = self._stack.enter_context(LocalCluster(
                    n_workers=self.n_workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                    silence_logs=level))
                self.client = self._stack.enter_context(Client(self.cluster, timeout=CONNECT_TIMEOUT_S))
            else:
                self.client = self._stack.enter_context(Client(self.scheduler, timeout=CONNECT_TIMEOUT_S))
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            self._stack.close()
            where = self.scheduler or "a local cluster"
            raise UserError(f"cannot reach the Dask scheduler at {where}: {exc}".replace("\n", " ")) from None
        self.start_s = time.perf_counter() - t0
        return self

    def __exit__(self, *exc):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            self._stack.close()
        return False

    @property
    def workers(self) -> int:
        if self.client is None:
            return 0
        return len(self.client.scheduler_info(n_workers=-1).get("workers", {}))

    # --- work
    def run(self, tasks: Sequence[BrickTask], progress: Progress | None = None) -> list[BrickResult]:
        """Every task's result, in task order; ``progress`` (cube4.progress) counts the bricks done."""
        from distributed import as_completed

        if self.client is None:
            raise RuntimeError("DaskExecutor.run outside its with-block")
        token = uuid.uuid4().hex[:8]
        keys = [f"cube4-brick-{token}-{n}" for n in range(len(tasks))]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")     # large task payloads (a brick's voxels) are intended
            futures = [self.client.submit(_run, t, self.journal, self.hold, key=k, retries=RETRIES, pure=False)
                       for t, k in zip(tasks, keys)]
        pos = {f.key: n for n, f in enumerate(futures)}
        out: list[BrickResult | None] = [None] * len(tasks)
        t_end = None if self.timeout is None else time.monotonic() + self.timeout
        try:
            for fut in counted(as_completed(futures, timeout=self.timeout), progress, "bricks", total=len(tasks)):
                left = None if t_end is None else max(1.0, t_end - time.monotonic())
                try:
                    out[pos[fut.key]] = fut.result(timeout=left)
                except UserError:
                    raise
                except Exception as exc:  # a task that failed RETRIES + 1 times, or lost too often
                    raise UserError(f"brick {tasks[pos[fut.key]].label} failed on the cluster: "
                                    f"{type(exc).__name__}: {exc}".replace("\n", " ")) from None
                fut.release()
        except TimeoutError:
            raise UserError(f"the cluster did not finish the frame's {len(tasks)} bricks in {self.timeout} s") from None
        finally:
            for f in futures:
                f.release()
        self._retries += self._count_retries(keys)
        return out  # type: ignore[return-value]

    def _count_retries(self, keys: list[str]) -> int:
        """Runs beyond the first of every task, from the scheduler's transition log."""
        try:
            story = self.client.story(*keys)
        except Exception:  # an older scheduler without stories: unknown, counted as none
            return 0
        runs: dict[str, int] = {}
        for entry in story:
            if len(entry) > 3 and entry[3] == "processing":
                runs[entry[1]] = runs.get(entry[1], 0) + 1
        return sum(max(0, n - 1) for n in runs.values())

    def stats(self) -> dict:
        return {"executor": self.name, "workers": self.workers, "retries": self._retries,
                "scheduler": self.scheduler or "local", "cluster_start_s": self.start_s}
