"""Where the points of a sweep run: in this process, in local processes, or on a Dask cluster.

All three executors have one method, :meth:`Executor.imap`, which applies a function to every item
of an iterable and yields ``(index, value)`` pairs, in the order of the items (or as they finish,
with ``ordered=False``).  A point that fails never stops the others: an exception raised by the
function becomes a :class:`Failure` value for that item, and so does a worker process that dies
(its items are re-run one at a time, so that only the point that kills a worker is lost).

Items are submitted lazily, a bounded window at a time, so that a sweep of millions of points does
not hold millions of futures.  ``distributed`` is imported only when a scheduler address is given.
"""
from __future__ import annotations

import collections
import os
from typing import Any, Callable, Iterable, Iterator, NamedTuple

from ._errors import BadInput, ClusterError, MissingPackage

INSTALL_HINT = "pip install 'viscosine[cluster]'"


class Failure(NamedTuple):
    """The value yielded for an item whose evaluation failed (picklable, no traceback)."""

    error: str


def _call_chunk(fn: Callable, chunk: list) -> list:
    """Evaluate fn on each item of a chunk, turning exceptions into Failure values."""
    out = []
    for item in chunk:
        try:
            out.append(fn(item))
        except Exception as exc:  # any failure of one point is that point's result
            out.append(Failure(f"{type(exc).__name__}: {exc}"))
    return out


class Executor:
    """Base class: windowed submission of chunks, failure isolation, ordered results.

    Subclasses provide ``_submit(fn, chunk) -> future``, ``_wait_first(futures) -> done set`` and
    ``workers`` (the parallelism, used to size the window).
    """

    workers = 1
    eager = False  # True when _submit computes the result itself (no parallelism)

    def imap(self, fn: Callable, items: Iterable, *, chunksize: int = 1,
             ordered: bool = True) -> Iterator[tuple[int, Any]]:
        """Yield ``(index, fn(item) or Failure)`` for every item.

        Parameters
        ----------
        fn : callable
            A picklable (module-level) function of one item.
        items : iterable
            Consumed lazily.
        chunksize : int
            Items per task (fewer round trips for cheap items).
        ordered : bool
            Yield in the order of the items (default) or as results arrive.
        """
        chunksize = max(1, int(chunksize))
        window = 4 * max(1, self.workers)            # chunks in flight
        if self.eager:  # evaluated at submission: one item at a time, so each shows at once
            chunksize = window = 1
        source = enumerate(items)
        retry = collections.deque()                  # (index, item) to re-run alone
        pending = {}                                 # future -> (list of (index, item), alone)
        ready = {}                                   # index -> value (ordered mode)
        next_index = 0
        exhausted = False

        def submit(job, alone):
            pending[self._submit(fn, [item for _, item in job])] = (job, alone)

        def fill():
            nonlocal exhausted
            if retry:  # isolation: a retried item runs with nothing else in flight
                if not pending:
                    submit([retry.popleft()], True)
                return
            while not exhausted and len(pending) < window:
                job = [pair for _, pair in zip(range(chunksize), source)]
                exhausted = len(job) < chunksize
                if job:
                    submit(job, False)

        fill()
        while pending:
            for fut in self._wait_first(list(pending)):
                job, alone = pending.pop(fut)
                try:
                    values = self._result(fut)
                except Exception as exc:  # the task failed as a whole: a worker died, ...
                    self._recover(fut, exc)
                    if not alone:
                        retry.extend(job)  # innocent neighbours are re-run, one at a time
                        continue
                    values = [Failure(_describe(exc))]
                for (i, _), v in zip(job, values):
                    if ordered:
                        ready[i] = v
                    else:
                        yield i, v
            if ordered:
                while next_index in ready:
                    yield next_index, ready.pop(next_index)
                    next_index += 1
            fill()

    # -- hooks --------------------------------------------------------------------------
    def _result(self, fut):
        return fut.result()

    def _recover(self, fut, exc) -> None:
        """Called after a task failed as a whole (e.g. replace a broken process pool)."""

    def close(self, wait: bool = True) -> None:
        """Release processes and connections (without waiting for running items if not wait)."""

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc):
        self.close(wait=exc_type is None)  # on Ctrl-C or an error, do not wait for the workers
        return False


def _describe(exc) -> str:
    if type(exc).__name__ in ("BrokenProcessPool", "KilledWorker"):
        return (f"{type(exc).__name__}: the worker process running this point died (a crash, or "
                "killed by the system, e.g. out of memory)")
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else 'the worker failed'}"


class _Done:
    """A finished 'future' for the serial executor."""

    def __init__(self, value):
        self.value = value

    def result(self):
        return self.value


class SerialExecutor(Executor):
    """Everything in this process, one item after the other."""

    eager = True

    def _submit(self, fn, chunk):
        return _Done(_call_chunk(fn, chunk))

    def _wait_first(self, futures):
        return futures[:1]


def _one_fft_thread():
    """A pool process's initializer: one FFT thread per process (the surface BEM's, read from
    VISCOSINE_FFT_THREADS), since the processes already fill the cores; a value the user set
    is kept."""
    os.environ.setdefault("VISCOSINE_FFT_THREADS", "1")


class ProcessExecutor(Executor):
    """A local pool of ``workers`` processes (concurrent.futures)."""

    def __init__(self, workers: int):
        self.workers = int(workers)
        self._pool = None

    def _pool_(self):
        from concurrent.futures import ProcessPoolExecutor
        if self._pool is None:
            self._pool = ProcessPoolExecutor(max_workers=self.workers,
                                             initializer=_one_fft_thread)
        return self._pool

    def _submit(self, fn, chunk):
        from concurrent.futures.process import BrokenProcessPool
        try:
            pool = self._pool_()
            fut = pool.submit(_call_chunk, fn, chunk)
        except BrokenProcessPool:  # broke since the last result was read: start afresh
            self._pool = None
            pool = self._pool_()
            fut = pool.submit(_call_chunk, fn, chunk)
        fut.viscosine_pool = pool
        return fut

    def _wait_first(self, futures):
        from concurrent.futures import FIRST_COMPLETED, wait
        return wait(futures, return_when=FIRST_COMPLETED).done

    def _recover(self, fut, exc):
        from concurrent.futures.process import BrokenProcessPool
        # only the pool that broke is replaced (stale futures of an old pool fail later)
        if isinstance(exc, BrokenProcessPool) and getattr(fut, "viscosine_pool", None) is self._pool:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None

    def close(self, wait=True):
        if self._pool is not None:
            self._pool.shutdown(wait=wait, cancel_futures=True)
            self._pool = None


class DaskExecutor(Executor):
    """A Dask distributed cluster reached through its scheduler address."""

    def __init__(self, address: str, timeout: float = 10.0):
        try:
            import distributed
        except ImportError:
            raise MissingPackage(f"--scheduler needs the Dask distributed package: {INSTALL_HINT}") from None
        self._distributed = distributed
        try:
            self._client = distributed.Client(address, timeout=timeout, set_as_default=False)
        except (OSError, TimeoutError, ValueError) as exc:
            raise ClusterError(f"--scheduler {address}: cannot connect ({_describe(exc)})") from None
        n = len(self._client.scheduler_info().get("workers", {}))
        self.workers = max(1, n)

    def _submit(self, fn, chunk):
        return self._client.submit(_call_chunk, fn, chunk, pure=False)

    def _wait_first(self, futures):
        with self._client.as_current():  # wait() uses the current client, not a global one
            return self._distributed.wait(futures, return_when="FIRST_COMPLETED").done

    def close(self, wait=True):
        self._client.close()


def executor(workers: int | None = None, scheduler: str | None = None) -> Executor:
    """The executor the command line asked for.

    Parameters
    ----------
    workers : int, optional
        Local processes; 1 or None runs in this process.
    scheduler : str, optional
        Address of a Dask scheduler (e.g. ``tcp://host:8786``); not together with ``workers``.

    Raises
    ------
    BadInput
        Both given, or workers < 1.
    MissingPackage
        distributed is not installed.
    ClusterError
        The scheduler cannot be reached.
    """
    if scheduler is not None and workers is not None:
        raise BadInput("--scheduler and --workers are not allowed together: the cluster decides "
                       "how many workers run")
    if scheduler is not None:
        return DaskExecutor(scheduler)
    if workers is not None and workers < 1:
        raise BadInput(f"workers={workers!r} is not allowed: an integer >= 1")
    if workers is None or workers == 1:
        return SerialExecutor()
    return ProcessExecutor(min(workers, 4 * (os.cpu_count() or 1)))
