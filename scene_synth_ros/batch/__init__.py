"""Batches of furnished rooms: thousands of rooms on every core of one machine, or on a Ray
cluster, written into one directory that a later run resumes (``scene-synth generate -n``,
``--layouts``, ``complete DIR``).

Room ``i`` of a batch is furnished with the seed ``seed + i`` in the ``i``-th room of its
source, and depends on nothing else that a run may change: not on the workers, their number,
``-n``, nor whether the room was made in this run or an earlier one. The modules, in the
order a room goes through them:

- ``sources``: which rooms a batch makes (corpus-like shells, a layout, a directory or a
  JSON-lines file of them) and how their documents are read;
- ``config``: what one batch is asked for (``BatchConfig``);
- ``worker``: one worker, which furnishes rooms in lockstep groups and makes their files and
  manifest rows;
- ``pool`` and ``ray_actors``: the workers as processes on this machine or as Ray actors;
- ``manifest``: the directory (``batch.json``, ``manifest.jsonl``, the rooms' files) and
  resumption;
- ``summary``: ``summary.json``;
- ``driver``: ``run_batch``, which checks a batch, runs it and writes what comes back.
"""
from .config import MAX_LOCKSTEP, BatchConfig
from .driver import run_batch
from .manifest import Manifest
from .sources import BatchError, RoomJob, Source, room_name, scene_from_document
from .summary import BatchSummary
from .worker import (
    GROUP_ROUNDS,
    RoomGroup,
    RoomResult,
    Worker,
    WorkerSpec,
    available_formats,
    group_size,
    output_files,
)

__all__ = [
    'GROUP_ROUNDS', 'MAX_LOCKSTEP', 'BatchConfig', 'BatchError', 'BatchSummary', 'Manifest',
    'RoomGroup', 'RoomJob', 'RoomResult', 'Source', 'Worker', 'WorkerSpec',
    'available_formats', 'group_size', 'output_files', 'room_name', 'run_batch',
    'scene_from_document',
]
