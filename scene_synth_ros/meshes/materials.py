"""The named PBR materials every catalog model is painted with.

A part refers to its material by name; ``MATERIALS`` maps each name to a base colour (RGBA,
0-255) plus metallic and roughness factors, which the exporters turn into glTF PBR materials
or MTL entries and the preview into flat shading. ``BOOK_COVERS`` is the palette for book
spines and magazines.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    """A plain PBR material: base colour (RGBA, 0-255), metallic and roughness factors."""

    name: str
    rgba: tuple[int, int, int, int]
    metallic: float = 0.0
    roughness: float = 0.7

    @property
    def transparent(self) -> bool:
        return self.rgba[3] < 255


def _m(name, r, g, b, a=255, metallic=0.0, roughness=0.7):
    return Material(name, (r, g, b, a), metallic, roughness)


MATERIALS: dict[str, Material] = {m.name: m for m in (
    _m('wood', 150, 105, 65), _m('wood_light', 206, 170, 122), _m('wood_dark', 92, 60, 38),
    _m('wood_white', 236, 233, 226, roughness=0.5), _m('paint_grey', 118, 122, 128),
    _m('paint_cream', 228, 218, 196, roughness=0.5), _m('shadow', 42, 36, 32, roughness=0.9),
    _m('fabric_grey', 122, 126, 134, roughness=0.95),
    _m('fabric_grey_light', 178, 180, 184, roughness=0.95),
    _m('fabric_dark', 48, 50, 56, roughness=0.95), _m('fabric_blue', 64, 92, 140, roughness=0.95),
    _m('fabric_beige', 204, 188, 158, roughness=0.95),
    _m('fabric_green', 86, 124, 94, roughness=0.95), _m('fabric_red', 152, 58, 52, roughness=0.95),
    _m('fabric_mustard', 214, 160, 52, roughness=0.95),
    _m('leather', 112, 68, 42, roughness=0.5), _m('leather_black', 30, 30, 32, roughness=0.45),
    _m('mattress', 242, 240, 232, roughness=0.95), _m('linen', 252, 252, 250, roughness=0.95),
    _m('blanket_blue', 150, 178, 212, roughness=0.95),
    _m('blanket_rose', 214, 170, 160, roughness=0.95),
    _m('blanket_green', 160, 190, 150, roughness=0.95),
    _m('metal', 172, 175, 180, metallic=0.8, roughness=0.35),
    _m('chrome', 214, 216, 220, metallic=1.0, roughness=0.15),
    _m('metal_dark', 58, 60, 66, metallic=0.6, roughness=0.45),
    _m('brass', 200, 160, 70, metallic=0.9, roughness=0.3),
    _m('plastic_black', 34, 34, 38, roughness=0.5),
    _m('plastic_white', 240, 240, 236, roughness=0.4),
    _m('plastic_grey', 150, 152, 156, roughness=0.5), _m('rubber', 28, 28, 28, roughness=0.9),
    _m('ceramic', 246, 246, 244, roughness=0.15),
    _m('ceramic_shadow', 200, 208, 214, roughness=0.15),
    _m('screen', 14, 16, 24, roughness=0.1), _m('screen_on', 40, 70, 110, roughness=0.1),
    _m('glass', 196, 222, 234, 90, roughness=0.05),
    _m('glass_dark', 40, 52, 64, 200, roughness=0.05),
    _m('mirror', 206, 220, 230, metallic=0.9, roughness=0.05),
    _m('water', 78, 150, 214, 140, roughness=0.05), _m('whiteboard', 252, 252, 252, roughness=0.2),
    _m('lacquer', 20, 20, 22, roughness=0.15), _m('lacquer_white', 244, 242, 238, roughness=0.15),
    _m('keys_white', 250, 250, 246, roughness=0.3), _m('keys_black', 16, 16, 16, roughness=0.3),
    _m('stone', 204, 198, 186, roughness=0.85), _m('brick', 150, 76, 56, roughness=0.9),
    _m('firebox', 26, 24, 24, roughness=0.9), _m('fire', 250, 130, 30, roughness=0.9),
    _m('leaf', 66, 132, 58, roughness=0.8), _m('leaf_dark', 38, 94, 44, roughness=0.8),
    _m('leaf_light', 112, 164, 70, roughness=0.8), _m('soil', 72, 52, 36, roughness=1.0),
    _m('terracotta', 182, 96, 60, roughness=0.9), _m('bark', 100, 70, 46, roughness=0.9),
    _m('shade', 246, 236, 212, roughness=0.9), _m('bulb', 255, 246, 214, roughness=0.3),
    _m('paper', 246, 242, 228, roughness=0.9),
    _m('red', 184, 46, 44, roughness=0.5), _m('blue', 46, 82, 160, roughness=0.5),
    _m('green', 52, 128, 72, roughness=0.5), _m('yellow', 230, 190, 60, roughness=0.5),
    _m('orange', 232, 124, 40, roughness=0.5), _m('purple', 112, 72, 144, roughness=0.5),
    _m('teal', 40, 140, 140, roughness=0.5),
    _m('fur', 168, 116, 70, roughness=1.0), _m('fur_light', 220, 186, 140, roughness=1.0),
    _m('apple', 192, 36, 36, roughness=0.4), _m('citrus', 244, 146, 28, roughness=0.6),
    _m('lemon', 240, 214, 60, roughness=0.6), _m('grape', 96, 40, 90, roughness=0.4),
    _m('bottle_green', 40, 96, 52, 220, roughness=0.1), _m('bottle_brown', 110, 60, 24, 230,
                                                              roughness=0.1),
    _m('liquid_dark', 70, 40, 20, roughness=0.2), _m('wine', 110, 18, 36, 220, roughness=0.1),
    _m('gravel', 176, 156, 124, roughness=1.0),
)}

BOOK_COVERS = ('red', 'blue', 'green', 'yellow', 'orange', 'purple', 'teal', 'wood_dark')
