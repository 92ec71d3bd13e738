"""When two spheres touch, against Yade 2023.02a (sphere_touch_side_by_side.py): which pairs of
a gap-free lattice begin a contact (|d|^2 summed in Yade's order), and real contacts holding on
while their penetration, taken after the square root, is zero though |d|^2 exceeds (r1 + r2)^2
(eight pairs: the four-lane geometry's test as well as the scalar one)."""
from pathlib import Path

import pytest

from talus import twin

SCRIPT = Path(__file__).parents[1] / "yade_twins" / "contact" / "sphere_touch_side_by_side.py"
needs_yade = pytest.mark.skipif(not twin.yade_available(), reason="yade is not installed")


def run(case, who):
    return twin.run(SCRIPT, {"case": case}, who)


def test_lattice_contacts_begin_as_in_yade_order():
    ours = run("lattice", "talus")
    # The lattice tells the two orders apart, and the contacts follow Yade's.
    assert ours["vectorised"] > ours["yade_order"] == len(ours["pairs"]) > 1000


def test_real_contacts_hold_at_zero_penetration():
    ours = run("hold", "talus")
    pairs = [[2 * k, 2 * k + 1] for k in range(8)]
    assert ours["overlapping"] == {"begun": 8, "after one step": pairs, "after two": pairs}
    assert ours["apart"] == {"begun": 0, "after one step": [], "after two": []}


@needs_yade
@pytest.mark.parametrize("case", ["lattice", "hold"])
def test_sphere_touch_matches_yade(case):
    assert run(case, "talus") == run(case, "yade")
