"""``summary.json``: what a run did, and what the directory holds, counted from its manifest."""
from __future__ import annotations

from dataclasses import asdict, dataclass

from .config import BatchConfig
from .manifest import Manifest


@dataclass
class BatchSummary:
    """What a run did (``this run``) and what the directory holds (every row)."""

    out: str
    requested: int
    furnished: int                  # this run
    failed: int                     # this run
    skipped: int                    # already there
    seconds: float                  # this run's wall time
    workers: int
    backend: str                    # 'processes' or 'ray'
    peak_mb: dict[str, float]       # peak resident memory of each of this run's workers
    rooms_ok: int = 0               # in the whole manifest
    rooms_failed: int = 0
    objects_per_room: float = 0.0
    valid: int = 0
    robot_kept: int = 0
    unit: str = 'rooms'             # what a row is: a room, or a whole house (``--houses``)

    @property
    def rooms_per_second(self) -> float:
        done = self.furnished + self.failed
        return done / self.seconds if self.seconds > 0 else 0.0

    def to_dict(self) -> dict:
        return {**asdict(self), 'rooms_per_second': round(self.rooms_per_second, 3)}

    def report(self) -> str:
        """A few lines for people."""
        u = self.unit
        lines = [f'{self.out}: {self.requested} {u} asked for; {self.furnished} furnished '
                 f'and {self.failed} failed in {self.seconds:.1f} s '
                 f'({self.rooms_per_second:.2f} {u}/s on {self.workers} '
                 f'{"Ray worker" if self.backend == "ray" else "worker process"}'
                 f'{"" if self.workers == 1 else "es" if self.backend != "ray" else "s"}), '
                 f'{self.skipped} already there']
        if self.rooms_ok:
            lines.append(f'the directory holds {self.rooms_ok} {u}, '
                         f'{self.objects_per_room:.2f} objects each; physically valid: '
                         f'{self.valid}, robot promise kept: {self.robot_kept}')
        if self.peak_mb:
            lines.append(f'peak memory per worker: {max(self.peak_mb.values()):.0f} MB at most')
        if self.rooms_failed:
            lines.append(f'{self.rooms_failed} {u} failed: their rows in manifest.jsonl say '
                         'why')
        return '\n'.join(lines)


def summarize(cfg: BatchConfig, manifest: Manifest, requested: int, furnished: int,
              failed: int, skipped: int, seconds: float, workers: int,
              peaks: dict[str, float]) -> BatchSummary:
    ok = [r for r in manifest.rows.values() if r.get('status') == 'ok']
    return BatchSummary(
        out=str(cfg.out), requested=requested, furnished=furnished, failed=failed,
        skipped=skipped, seconds=round(seconds, 3), workers=workers,
        backend='ray' if cfg.ray else 'processes', peak_mb=peaks,
        rooms_ok=len(ok), rooms_failed=len(manifest.rows) - len(ok),
        objects_per_room=round(sum(r.get('objects', 0) for r in ok) / len(ok), 3) if ok else 0.0,
        valid=sum(bool(r.get('valid')) for r in ok),
        robot_kept=sum(bool(r.get('robot_kept')) for r in ok),
        unit='houses' if cfg.source.kind == 'plans' else 'rooms')
