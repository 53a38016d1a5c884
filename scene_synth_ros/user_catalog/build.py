"""A folder of the user's meshes measured into a catalog, with a report of what was kept
and what was left out and why (one line per model left out)."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .. import catalog
from ..catalog import Catalog, UserModel
from ..categories import CATEGORIES, PAPER, Vocabulary
from ..errors import number, quoted, sentence
from .measure import measure
from .sources import find_specs


@dataclass
class BuildReport:
    """The models measured, and one line (a bounded sentence) per model left out."""

    models: list[UserModel] = field(default_factory=list)
    lines: list[str] = field(default_factory=list)

    def catalog(self, source: str | None = None) -> Catalog:
        return Catalog(self.models, source)

    def text(self) -> str:
        """The report as the command line prints it."""
        out = [f'{m.model_id:24s} {m.category:16s} {number(m.width):>6s} x '
               f'{number(m.depth):>6s} x {number(m.height):>6s} m' for m in self.models]
        covered = self.catalog().user_categories
        out.append(f'kept {len(self.models)} models of {len(covered)} categories'
                   f'{": " + ", ".join(covered) if covered else ""}; left out '
                   f'{len(self.lines)}{":" if self.lines else ""}')
        out += [f'  {line}' for line in self.lines]
        fallback = [c for c in CATEGORIES if c not in covered]
        out.append(f'{len(fallback)} categories keep the procedural models')
        return '\n'.join(out)


def build_catalog(folder: str | Path, manifest: str | Path | None = None,
                  category_map: str | Path | None = None, vocabulary: Vocabulary = PAPER
                  ) -> BuildReport:
    """Measure every model ``folder`` offers (``sources.find_specs``), of the categories of
    ``vocabulary``. Raises ``CatalogError`` only when nothing can be read at all."""
    specs, lines = find_specs(folder, manifest, category_map, vocabulary)
    report = BuildReport(lines=[sentence(line) for line in lines])
    taken: dict[str, str] = {}
    for spec in specs:
        where = quoted(spec.name, 60)
        if spec.model_id in taken:
            report.lines.append(sentence(f'{where}: its id {quoted(spec.model_id)} is already '
                                         f'{quoted(taken[spec.model_id], 60)}\'s'))
            continue
        try:
            catalog.get(spec.model_id, vocabulary)
        except KeyError:
            pass
        else:
            report.lines.append(sentence(f'{where}: its id {quoted(spec.model_id)} is a '
                                         f'procedural model\'s; give it another id'))
            continue
        model = measure(spec, vocabulary)
        if isinstance(model, str):
            report.lines.append(sentence(f'{where}: {model}'))
            continue
        taken[spec.model_id] = spec.name
        report.models.append(model)
    return report
