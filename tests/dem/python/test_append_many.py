"""O.bodies.append of a list: the per-body tables of the Python side (appearance, reference
states) grow once for the whole list, not once per body (which made building a scene of N bodies
take N^2 time: minutes at 200 000 spheres), and every body gets its own look and reference."""
import numpy as np

from talus.dem import Scene, sphere
from talus.dem.geometry.appearance import Appearance
from talus.dem.core.reference import ReferenceStates


def test_a_list_grows_the_tables_once_and_each_body_gets_its_own_entries(monkeypatch):
    grown = []
    for table in (Appearance, ReferenceStates):
        ensure = table.ensure

        def counting(self, count, ensure=ensure, table=table):
            before = len(self.color if table is Appearance else self.pos)
            ensure(self, count)
            if count > before:
                grown.append((table.__name__, count))
        monkeypatch.setattr(table, "ensure", counting)
    S = Scene()
    S.bodies.append(sphere((0, 0, 0), 1))
    grown.clear()
    ids = S.bodies.append([sphere((3.0 * k, 0, 0), 1, color=(0, 0, k / 500)) for k in range(1, 501)])
    assert sorted(grown) == [("Appearance", 501), ("ReferenceStates", 501)]
    assert ids == list(range(1, 501))
    assert len(S._appearance.color) == len(S._reference.pos) == 501
    assert np.allclose(S._appearance.color[1:, 2], np.arange(1, 501) / 500)
    assert np.allclose([S.bodies[i].state.refPos[0] for i in (1, 250, 500)], [3.0, 750.0, 1500.0])
