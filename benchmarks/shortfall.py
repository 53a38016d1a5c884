"""Why synthesized rooms hold fewer objects than the corpus (the shortfall bench_synth shows).

For every room type, ``-n`` rooms are synthesized from empty into the same held-out shells
with the same seeds as ``bench_synth.py`` (its ``_synthesize``: corpus seed 1, room i, seed
i), while the synthesizer's steps are counted by wrapping its methods on the instance and the
checks ``fits`` calls in ``scene_synth_ros.synth`` (in this process only). Tables:

1. how rooms end (STOP drawn / nothing fits / max objects), objects per room against the
   shells' own corpus rooms and the training corpus (seed 0), KL(synth || corpus);
2. per category, count per room synthesized vs corpus, by absolute difference;
3. each step's outcome (placed or STOP at the first category draw or after failed ones), and
   per category how often a drawn category fails to insert (``_insert_category`` returns
   None): for an empty location mask, or after every location try failed, where a try fails
   for no supporting parent under the point or because ``fits`` rejected every model (by the
   last check ``fits`` ran: floor (left the floor), collide, door, rules (a design rule kept
   at insertion), path (the robot promise), support, sibling);
4. rooms ended by STOP: objects then against the shell's corpus room, and p(STOP) at the
   draw as ``_next_category`` computes it (with the mask of that draw, the step's first mask,
   no mask), and p(STOP) of the shell's corpus room cut to as many objects (training order);
5. p(STOP) by objects present: at synthesized steps, on corpus prefixes (every prefix of
   every shell's corpus room, training order), the observed rate at which those prefixes are
   complete, and that rate as the training examples weight it (one prefix per room drawn
   uniformly, so a room of N objects weighs 1 / (N + 1) per prefix).

    .venv/bin/python benchmarks/shortfall.py [-n 150] [--room-type all] [--corpus-rooms 2000]
"""
import argparse
from collections import Counter, defaultdict
from pathlib import Path
import statistics
import sys

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / 'benchmarks'))

import bench_synth  # noqa: E402
import numpy as np  # noqa: E402
import shapely  # noqa: E402
import torch  # noqa: E402

from scene_synth_ros import synth as synth_module  # noqa: E402
from scene_synth_ros.categories import CATEGORIES, ROOM_TYPES, kl_divergence  # noqa: E402
from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import generate_corpus, generate_room  # noqa: E402
from scene_synth_ros.corpus.stats import collect  # noqa: E402
from scene_synth_ros.networks.category import category_probabilities  # noqa: E402
from scene_synth_ros.networks.examples import insertion_order  # noqa: E402
from scene_synth_ros.scene import Scene  # noqa: E402

REASONS = ('floor', 'collide', 'door', 'rules', 'path', 'support', 'sibling')
# The checks ``fits`` makes, by the name it calls them under in ``scene_synth_ros.synth``
# (the design rules kept at insertion are wrapped one by one: 'rules'; the robot promise,
# ``robot.state_after``: 'path').
CHECKS = {'overlaps_any': 'collide', 'enters_zone': 'door', 'support_fraction': 'support'}


def watch_fits_checks(note, rule_label=lambda name: 'rules') -> None:
    """Have each check ``Synthesizer.fits`` makes call ``note(label)`` before it runs
    (``CHECKS``; each design rule kept at insertion as ``rule_label(name)``; the robot
    promise as 'path'), by wrapping them in ``scene_synth_ros.synth`` (this process only):
    after a refusal the last label noted names the check that refused, none noted since the
    call the floor, which ``fits`` checks first."""
    def watched(fn, label):
        def wrapped(*a, **k):
            note(label)
            return fn(*a, **k)
        return wrapped

    for fn, label in CHECKS.items():
        setattr(synth_module, fn, watched(getattr(synth_module, fn), label))
    rules = synth_module.INSERTION_RULES
    for name in rules:
        rules[name] = watched(rules[name], rule_label(name))
    robot = synth_module.robot
    robot.state_after = watched(robot.state_after, 'path')


class Probe:
    """Counts what each step of a ``Synthesizer`` does, by wrapping it."""

    WRAPPED = ('_insert_one', '_next_category', '_insert_category', '_insert_model',
               '_parent', 'fits')

    def __init__(self, synth):
        self.orig = {name: getattr(synth, name) for name in self.WRAPPED}
        for name in self.WRAPPED:
            setattr(synth, name, getattr(self, name.lstrip('_')))
        watch_fits_checks(lambda label: setattr(self, 'last_check', label))
        location = synth_module.location_distribution

        def location_distribution(*a, **k):
            p = location(*a, **k)
            self.draw['mask'] += p is None
            return p
        synth_module.location_distribution = location_distribution
        self.per_category = defaultdict(Counter)     # category -> counts
        self.poke = defaultdict(list)                # category -> metres through the wall
        self.steps: list[dict] = []

    def insert_one(self, ctx, scene, allow_stop=True, only=None):
        self.step = {'n': len(scene.objects), 'draws': 0}
        obj, why = self.orig['_insert_one'](ctx, scene, allow_stop, only)
        self.step['outcome'] = why
        self.steps.append(self.step)
        return obj, why

    def next_category(self, ctx, logits, allowed):
        p = float(category_probabilities(logits, allowed)[-1])
        s = self.step
        s['draws'] += 1
        if s['draws'] == 1:
            s['p_first'], s['p_raw'] = p, float(torch.softmax(logits, -1)[-1])
        s['p_drawn'] = p
        return self.orig['_next_category'](ctx, logits, allowed)

    def insert_category(self, ctx, scene, c, location, small):
        self.draw, self.draw_poke = Counter(), []
        obj = self.orig['_insert_category'](ctx, scene, c, location, small)
        tally = self.per_category[ctx.spec.names[c]]
        tally['draws'] += 1
        if obj is None:
            tally['fails'] += 1
            tally.update(self.draw)
            self.poke[ctx.spec.names[c]] += self.draw_poke
        return obj

    def insert_model(self, *args):
        self.draw['tries'] += 1
        return self.orig['_insert_model'](*args)

    def parent(self, *args):
        p = self.orig['_parent'](*args)
        self.draw['noparent'] += p is None
        return p

    def fits(self, ctx, scene, obj, parent=None):
        self.last_check = 'floor'
        ok = self.orig['fits'](ctx, scene, obj, parent)
        if not ok:
            why = self.last_check
            if why == 'floor':      # how far the farthest corner pokes out of the floor
                corners = shapely.points(np.asarray(obj.footprint().exterior.coords))
                self.draw_poke.append(float(shapely.distance(ctx.floor, corners).max()))
            self.draw['rej:' + ('sibling' if why == 'collide' and obj.support else why)] += 1
        return ok


def corpus_stop_probs(synth, scene: Scene, seed: int) -> list[float]:
    """p(STOP) the category module gives every prefix (0 .. N objects) of ``scene`` in the
    order its training examples use, masked as ``_insert_one`` masks it."""
    ctx = synth._context(scene.room, seed)
    order = insertion_order(scene, np.random.default_rng(seed), by_importance=True)
    prefixes = [Scene(scene.room, order[:k]) for k in range(len(order) + 1)]
    render = synth._renderer(ctx.frame.resolution).render
    images = torch.from_numpy(np.stack([render(s, ctx.frame) for s in prefixes]))
    counts = torch.cat([synth._bag_of_categories(ctx, s) for s in prefixes])
    with torch.inference_mode():
        logits = ctx.bundle.networks['category'](images, counts)
    return [float(category_probabilities(lg, synth._allowed_categories(ctx, s, True))[-1])
            for lg, s in zip(logits, prefixes, strict=True)]


def run(probe: Probe, rt: str, n: int, corpus_rooms: int) -> dict:
    synth = bench_synth._SYNTH
    probe.per_category, probe.poke = defaultdict(Counter), defaultdict(list)
    rooms = []
    for i in range(n):
        probe.steps = []
        _, counts, nobj, viol, stopped = bench_synth._synthesize((rt, i))
        shell = generate_room(rt, HELDOUT_SEED, i)
        rooms.append({'counts': counts, 'n': nobj, 'stopped': stopped, 'steps': probe.steps,
                      'collisions': viol['collisions'], 'shell': shell,
                      'shell_n': len(shell.objects),
                      'prefix_p': corpus_stop_probs(synth, shell, i)})
    corpus = collect(rt, generate_corpus(rt, corpus_rooms, seed=0, workers=1), check=False)
    return {'rooms': rooms, 'corpus': corpus, 'per_category': probe.per_category,
            'poke': probe.poke}


def mean(xs) -> float:
    xs = list(xs)
    return sum(xs) / len(xs) if xs else float('nan')


def table_ends(res):
    print('\n1. how rooms end; objects per room (shell: the same shells\' corpus rooms, '
          'corpus: seed 0)')
    print(f'{"room type":10s} {"rooms":>5s} {"stop":>5s} {"nothing":>7s} {"max":>4s} '
          f'{"syn":>6s} {"shell":>6s} {"corpus":>6s} {"diff":>6s} {"KL":>7s} {"collide":>7s}')
    for rt, r in res.items():
        rooms, corpus = r['rooms'], r['corpus']
        s = Counter(x['stopped'] for x in rooms)
        syn = mean(x['n'] for x in rooms)
        total = Counter()
        for x in rooms:
            total.update(x['counts'])
        kl = kl_divergence({c: v / sum(total.values()) for c, v in total.items()},
                           corpus.distribution())
        print(f'{rt:10s} {len(rooms):5d} {s["stop"]:5d} {s["nothing_fits"]:7d} '
              f'{s["max_objects"]:4d} {syn:6.2f} {mean(x["shell_n"] for x in rooms):6.2f} '
              f'{corpus.objects_per_room:6.2f} {syn / corpus.objects_per_room - 1:+6.1%} '
              f'{kl:7.4f} {sum(x["collisions"] for x in rooms):7d}')


def table_categories(res, top):
    print(f'\n2. count per room by category, the {top} largest |syn - corpus| (t: tier)')
    print(f'{"room type":10s} {"category":15s} {"t":1s} {"syn":>6s} {"shell":>6s} '
          f'{"corpus":>6s} {"diff":>6s}')
    for rt, r in res.items():
        rooms, corpus = r['rooms'], r['corpus']
        syn, shell = Counter(), Counter()
        for x in rooms:
            syn.update(x['counts'])
            shell.update(o.category for o in x['shell'].objects)
        n = len(rooms)
        rows = [(c, syn[c] / n, shell[c] / n, corpus.frequency(c))
                for c in set(syn) | set(corpus.counts)]
        rows.sort(key=lambda t: -abs(t[1] - t[3]))
        for c, s, h, k in rows[:top]:
            print(f'{rt:10s} {c:15s} {CATEGORIES[c].tier[0]} {s:6.3f} {h:6.3f} {k:6.3f} '
                  f'{s - k:+6.3f}')
        d = [t[1] - t[3] for t in rows]
        print(f'{rt:10s} {"(all: missing":15s}   {sum(x for x in d if x < 0):+6.3f}, over '
              f'{sum(x for x in d if x > 0):+6.3f})')


def table_failures(res, top):
    print('\n3a. step outcomes, % of steps (@1: at the first category draw, @2+: after failed '
          'draws)')
    print(f'{"room type":10s} {"steps":>6s} {"placed@1":>8s} {"placed@2+":>9s} {"stop@1":>6s} '
          f'{"stop@2+":>7s} {"nothing":>7s}')
    for rt, r in res.items():
        steps = [s for x in r['rooms'] for s in x['steps']]
        kind = Counter(s['outcome'] + ('' if s['outcome'] == 'nothing_fits' else
                                       '@1' if s['draws'] == 1 else '@2+') for s in steps)
        print(f'{rt:10s} {len(steps):6d} ' + ' '.join(
            f'{kind[k] / len(steps):{w}.1%}' for k, w in
            (('placed@1', 8), ('placed@2+', 9), ('stop@1', 6), ('stop@2+', 7),
             ('nothing_fits', 7))))
    print(f'\n3b. failed category draws, the {top} most failing categories: fail% of draws; '
          'of the failed: mask% (empty mask),\n    tries per failed draw, and the failed '
          'tries by cause, % (noparent, then the rejecting check of fits);\n    for the floor '
          'rejections, how far the footprint leaves the floor (+1 cm tolerance): median, and '
          'share < 15 cm (wall_reach)')
    print(f'{"room type":10s} {"category":15s} {"t":1s} {"draws":>5s} {"fails":>5s} '
          f'{"fail%":>6s} {"mask%":>5s} {"tries":>5s} {"nopar":>5s} '
          + ' '.join(f'{r[:7]:>7s}' for r in REASONS) + f' {"out cm":>6s} {"<15cm":>5s}')
    for rt, r in res.items():
        pc = dict(r['per_category'])
        pc['(all)'] = sum(pc.values(), Counter())
        poke = dict(r['poke'], **{'(all)': [v for x in r['poke'].values() for v in x]})
        rows = sorted(pc.items(), key=lambda t: -t[1]['fails'])[:top + 1]
        for c, t in rows:
            if not t['fails']:
                break
            out = poke.get(c)
            out = (f' {100 * statistics.median(out):6.1f} {mean(v < 0.15 for v in out):5.0%}'
                   if out else f' {"-":>6s} {"-":>5s}')
            fails = max(t['fails'], 1)
            rej = sum(t['rej:' + k] for k in REASONS)
            causes = [t['noparent']] + [t['rej:' + k] for k in REASONS]
            share = [v / max(t['noparent'] + rej, 1) for v in causes]
            tier = CATEGORIES[c].tier[0] if c in CATEGORIES else ' '
            print(f'{rt:10s} {c:15s} {tier} {t["draws"]:5d} {t["fails"]:5d} '
                  f'{t["fails"] / max(t["draws"], 1):6.1%} {t["mask"] / fails:5.0%} '
                  f'{t["tries"] / fails:5.1f} {share[0]:5.0%} '
                  + ' '.join(f'{v:7.0%}' for v in share[1:]) + out)


def table_stop(res):
    print('\n4. rooms ended by STOP: objects then vs the shell\'s corpus room; p(STOP) at the '
          'draw (drawn: that draw\'s mask,\n   first: the step\'s first mask, raw: no mask), '
          'on the shell\'s corpus room cut to as many objects (prefix);\n   corr: correlation '
          'of the objects synthesized and in the shell\'s corpus room, over all rooms')
    print(f'{"room type":10s} {"rooms":>5s} {"syn":>5s} {"shell":>5s} {"diff":>5s} '
          f'{"fewer":>5s} {"equal":>5s} {"more":>5s} {"drawn":>5s} {"med":>5s} {"first":>5s} '
          f'{"raw":>5s} {"@2+":>5s} {"prefix":>6s} {"corr":>5s}')
    for rt, r in res.items():
        rooms = [x for x in r['rooms'] if x['stopped'] == 'stop']
        last = [x['steps'][-1] for x in rooms]
        d = [x['n'] - x['shell_n'] for x in rooms]
        shell_n = [x['shell_n'] for x in r['rooms']]
        pre = [x['prefix_p'][x['n']] for x in rooms if x['n'] <= x['shell_n']]
        print(f'{rt:10s} {len(rooms):5d} {mean(x["n"] for x in rooms):5.2f} '
              f'{mean(x["shell_n"] for x in rooms):5.2f} {mean(d):+5.2f} '
              f'{mean(v < 0 for v in d):5.0%} {mean(v == 0 for v in d):5.0%} '
              f'{mean(v > 0 for v in d):5.0%} {mean(s["p_drawn"] for s in last):5.2f} '
              f'{statistics.median(s["p_drawn"] for s in last):5.2f} '
              f'{mean(s["p_first"] for s in last):5.2f} {mean(s["p_raw"] for s in last):5.2f} '
              f'{mean(s["draws"] > 1 for s in last):5.0%} {mean(pre):6.2f} '
              f'{statistics.correlation([x["n"] for x in r["rooms"]], shell_n):5.2f}')


def implied_objects(hazard: dict[int, float]) -> float:
    """Mean objects of rooms that stop after k objects with probability ``hazard[k]`` (and
    after the last k given, if not before)."""
    alive, expect = 1.0, 0.0
    for k in range(max(hazard) + 1):
        expect += k * alive * hazard.get(k, 1.0)
        alive *= 1 - hazard.get(k, 1.0)
    return expect + alive * (max(hazard) + 1)


def table_calibration(res):
    print('\n5. p(STOP) by objects present k: mean at synthesized steps (syn, first mask) and '
          'on the shells\' corpus prefixes (cor),\n   the observed share of those prefixes '
          'that are the whole room (obs) and that share as training weighs it (train);\n'
          '   then the mean objects per room each of these stopping rates implies')
    print(f'{"room type":10s} {"k":>5s} {"n syn":>5s} {"syn":>5s} {"n cor":>5s} {"cor":>5s} '
          f'{"obs":>5s} {"train":>5s}')
    for rt, r in res.items():
        syn, cor = defaultdict(list), defaultdict(list)     # k -> p / (p, complete, weight)
        for x in r['rooms']:
            for s in x['steps']:
                syn[s['n']].append(s['p_first'])
            for k, p in enumerate(x['prefix_p']):
                cor[k].append((p, k == x['shell_n'], 1 / (x['shell_n'] + 1)))
        for b in range(0, max(cor) + 1, 2):
            ps = syn.get(b, []) + syn.get(b + 1, [])
            c = cor.get(b, []) + cor.get(b + 1, [])
            if len(c) + len(ps) >= 20:
                print(f'{rt:10s} {f"{b}-{b + 1}":>5s} {len(ps):5d} {mean(ps):5.2f} {len(c):5d} '
                      f'{mean(t[0] for t in c):5.2f} {mean(t[1] for t in c):5.2f} '
                      f'{sum(t[2] for t in c if t[1]) / sum(t[2] for t in c):5.2f}')
        implied = {
            'syn': {k: mean(v) for k, v in syn.items() if v},
            'cor': {k: mean(t[0] for t in v) for k, v in cor.items()},
            'obs': {k: mean(t[1] for t in v) for k, v in cor.items()},
            'train': {k: sum(t[2] for t in v if t[1]) / sum(t[2] for t in v)
                      for k, v in cor.items()}}
        every = [t for v in cor.values() for t in v]
        print(f'{rt:10s} all prefixes: cor {mean(t[0] for t in every):.3f} vs obs '
              f'{mean(t[1] for t in every):.3f}; implied objects per room: ' + ', '.join(
                  f'{k} {implied_objects(h):.2f}' for k, h in implied.items())
              + f' (synthesized {mean(x["n"] for x in r["rooms"]):.2f})')


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=150, help='synthesized rooms per room type')
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--corpus-rooms', type=int, default=2000)
    ap.add_argument('--top', type=int, default=10, help='rows per room type in tables 2 and 3')
    ap.add_argument('--weights-dir', default=None)
    args = ap.parse_args()
    bench_synth._init_worker(args.weights_dir)          # one torch thread, one Synthesizer
    probe = Probe(bench_synth._SYNTH)
    res = {}
    for rt in (list(ROOM_TYPES) if args.room_type == 'all' else [args.room_type]):
        print(f'{rt}: {args.n} rooms ...', file=sys.stderr, flush=True)
        res[rt] = run(probe, rt, args.n, args.corpus_rooms)
    table_ends(res)
    table_categories(res, args.top)
    table_failures(res, args.top)
    table_stop(res)
    table_calibration(res)


if __name__ == '__main__':
    main()
