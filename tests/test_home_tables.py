"""The tables of ``home_tables``: well formed, their names the package's categories, and,
with the real files of ``../shared/data/real`` beside the repository (skipped without them,
as ``test_datasets_real.py`` is), equal to what ``benchmarks/home_tables.py`` derives from
those files."""
from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from scene_synth_ros import home_tables as ht
from scene_synth_ros.categories import CATEGORIES, HOME_ROOM_TYPES, ROOM_TYPES
from scene_synth_ros.datasets.records import normalise_category

ROOT = Path(__file__).resolve().parent.parent
REAL = ROOT.parent / 'shared' / 'data' / 'real'
BENCHMARK = ROOT / 'benchmarks' / 'home_tables.py'
NAMES = {name for table in ht.TABLE_COUNTS.values() for name in table}


def test_every_table_counts_positive_objects_over_its_rooms():
    assert set(ht.TABLE_COUNTS) == set(ht.ROOMS_IN_TABLE)
    assert set(ht.TABLE_COUNTS) == set(HOME_ROOM_TYPES)
    for rt, table in ht.TABLE_COUNTS.items():
        rooms = ht.ROOMS_IN_TABLE[rt]
        assert isinstance(rooms, int) and rooms > 0, rt
        assert table, rt
        for name, count in table.items():
            assert isinstance(count, int) and count > 0, (rt, name)
            assert count <= 10 * rooms, (rt, name, count, rooms)   # objects per room, sane
        assert list(table.values()) == sorted(table.values(), reverse=True), rt


def test_names_are_written_as_the_packages_categories():
    for name in NAMES:
        assert name == normalise_category(name), name


def test_every_mapping_lands_on_a_table_name_or_a_category():
    kitchen, dining = set(ht.TABLE_COUNTS['kitchen']), set(ht.TABLE_COUNTS['dining'])
    assert set(ht.PROCTHOR_KITCHEN.values()) <= kitchen
    assert {name for name, _ in ht.PROCTHOR_COUNTER_SHAPES.values()} <= kitchen
    assert {n for _, *names in ht.PROCTHOR_KITCHEN_BY_HEIGHT.values() for n in names} <= kitchen
    assert set(ht.KITCHEN_REFERENCE) <= kitchen
    assert set(ht.FRONT_DINING.values()) <= dining
    # a data category is mapped or dropped, never both
    decided = [ht.PROCTHOR_KITCHEN, ht.PROCTHOR_KITCHEN_BY_HEIGHT, ht.PROCTHOR_COUNTER_TYPES,
               ht.PROCTHOR_KITCHEN_DROPPED]
    assert sum(len(d) for d in decided) == len(set().union(*decided))
    for share in ht.KITCHEN_REFERENCE.values():
        assert 0 < share <= 1


@pytest.mark.skipif('counter' not in CATEGORIES,
                    reason='issue 35\'s categories (the kitchen\'s counter, ...) not in '
                           'categories.CATEGORIES yet')
def test_every_name_is_a_known_category():
    assert NAMES <= set(CATEGORIES), sorted(NAMES - set(CATEGORIES))


def test_room_sizes_are_ordered_quantiles():
    assert set(ht.ROOM_SIZES) <= {*ROOM_TYPES, *ht.TABLE_COUNTS}
    assert ht.SIZE_QUANTILES == tuple(sorted(ht.SIZE_QUANTILES))
    for rt, sizes in ht.ROOM_SIZES.items():
        assert sizes.rooms == sum(sizes.sources.values()) > 0, rt
        for what in (sizes.longer, sizes.shorter, sizes.area):
            assert len(what) == len(ht.SIZE_QUANTILES), rt
            assert list(what) == sorted(what) and what[0] > 0, rt
        # each room's shorter side is at most its longer one, so each quantile is too
        assert all(s <= lo for s, lo in zip(sizes.shorter, sizes.longer, strict=True)), rt
        # a floor of at least 2 m² (schema.check_floor) inside the square of its longer side
        assert sizes.area[0] >= 2.0 and sizes.area[-1] <= sizes.longer[-1] ** 2, rt


def _benchmark():
    spec = importlib.util.spec_from_file_location('bench_home_tables', BENCHMARK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope='module')
def derived():
    if not REAL.is_dir():
        pytest.skip(f'no real data in {REAL}')
    return _benchmark().derive(REAL)


def test_the_data_derived_tables_are_what_the_data_gives(derived):
    for rt, (rooms, table) in derived['counts'].items():
        assert rooms == ht.ROOMS_IN_TABLE[rt], rt
        assert table == ht.TABLE_COUNTS[rt], rt
    assert not any(derived['undecided'].values()), derived['undecided']


def test_the_room_sizes_are_what_the_data_gives(derived):
    assert derived['sizes'] == ht.ROOM_SIZES

