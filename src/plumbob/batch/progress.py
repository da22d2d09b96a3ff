"""What a batch says while it runs and when it ends.

A progress bar with rate and ETA (rich, from the batch extra) only when stderr is a
terminal; nothing at all when it is not, so logs and pipes stay clean. The summary
counts files by status and failures by error, with the time and the rate.
"""

from __future__ import annotations

import sys
import time
from collections import Counter
from dataclasses import dataclass, field

__all__ = ["Summary", "Progress"]


@dataclass
class Summary:
    """Counts of a finished (or interrupted) batch."""

    files: int = 0
    resumed: int = 0
    computed: int = 0
    statuses: Counter = field(default_factory=Counter)
    errors: Counter = field(default_factory=Counter)
    seconds: float = 0.0

    def add(self, row: dict, computed: bool = True) -> None:
        """Count a row: one measured now, or (``computed`` False) kept from before."""
        self.computed += computed
        self.resumed += not computed
        status = row.get("status") or "ok"
        self.statuses[status] += 1
        if status != "ok":
            self.errors[row.get("error") or status] += 1

    @property
    def ok(self) -> bool:
        return set(self.statuses) <= {"ok"}

    def text(self) -> str:
        rate = self.computed / self.seconds if self.seconds > 0 else 0.0
        counts = ", ".join(f"{n} {s}" for s, n in sorted(self.statuses.items())) or "nothing to do"
        line = (f"plumbob batch: {self.files} file(s): {counts}; {self.computed} measured in "
                f"{self.seconds:.1f} s ({rate:.1f} files/s)")
        if self.resumed:
            line += f"; {self.resumed} of them done before, kept"
        if self.errors:
            line += "\n  not ok: " + ", ".join(f"{n} {e}" for e, n in self.errors.most_common())
        return line


class Progress:
    """A progress bar on a terminal, silence elsewhere (``enabled`` None: decide by tty)."""

    def __init__(self, total: int, enabled: bool | None = None) -> None:
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.total = total
        self.done = 0
        self.start = time.monotonic()
        self._bar = None
        self._task = None

    def __enter__(self) -> Progress:
        if not self.enabled:
            return self
        try:
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                TaskProgressColumn,
                TextColumn,
                TimeRemainingColumn,
            )
            from rich.progress import Progress as Bar
        except ImportError:
            return self
        self._bar = Bar(TextColumn("plumbob batch"), BarColumn(), MofNCompleteColumn(),
                        TaskProgressColumn(), TextColumn("{task.fields[rate]}"),
                        TimeRemainingColumn(), auto_refresh=False, transient=True,
                        console=Console(stderr=True))
        self._bar.__enter__()
        self._task = self._bar.add_task("files", total=self.total, rate="")
        return self

    def advance(self) -> None:
        self.done += 1
        if not self.enabled:
            return
        rate = self.done / max(time.monotonic() - self.start, 1e-9)
        if self._bar is not None:
            self._bar.update(self._task, advance=1, rate=f"{rate:.1f} files/s")
            self._bar.refresh()
        else:
            sys.stderr.write(f"\rplumbob batch: {self.done}/{self.total} ({rate:.1f} files/s)")
            sys.stderr.flush()

    def __exit__(self, *exc) -> None:
        if self._bar is not None:
            self._bar.__exit__(*exc)
        elif self.enabled:
            sys.stderr.write("\n")
