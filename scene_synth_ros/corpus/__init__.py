"""The procedural corpus: furnished rooms drawn from a seed and a room index by the paper's
per-room-type rules, standing in for SUNCG as training data and as the evaluation's real
rooms; ``generate`` makes them, ``stats`` compares them with the paper's table."""

HELDOUT_SEED = 1   # training reads corpus seed 0, so rooms of this seed test generalisation
