"""``O.bodies``: the scene's bodies as Yade scripts use them (append, index, erase, clump)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

import numpy as np

from talus import _dem
from talus.dem import distributed
from talus.dem.core import clumps
from talus.dem.geometry.appearance import Appearance
from talus.dem.core.bodies import Body, BodySpec, sphere
from talus.dem.core.reference import ReferenceStates
from talus.dem.files import slabs
from talus.dem.geometry.shape_registry import shape_kind

if TYPE_CHECKING:
    from talus.dem.core.scene import Scene


class BodyContainer:
    """``O.bodies``: append specs, index bodies by id, erase; bulk arrays for couplings."""

    def __init__(self, scene: "Scene"):
        self._scene = scene
        self._views: list[Body | None] = []     # by row, see _view

    def append(self, spec: BodySpec | Iterable[BodySpec]):
        """Add one body (returns its id) or a list of bodies (returns their ids)."""
        if distributed.is_split(self._scene):
            distributed.refuse("O.bodies.append after the scene was split (at its first step under mpirun)")
        if isinstance(spec, BodySpec):
            return self._add(spec)
        if slabs.is_slab(spec):     # under mpirun: this process's part of a file's spheres
            return distributed.append_slab(self, spec)
        return self._append_specs(list(spec))

    def insertAtId(self, spec: BodySpec, id: int) -> int:
        """Add ``spec`` as body ``id`` (Yade's, which Yade's mpy scripts use to build each
        process's bodies); the ids between the last body and ``id`` are left as erased bodies.
        Returns ``id``."""
        if isinstance(id, bool) or not isinstance(id, (int, np.integer)) or id < 0:
            raise ValueError(f"O.bodies.insertAtId: id must be an integer >= 0, got {id!r}")
        if distributed.domain(self._scene) is not None:
            distributed.refuse("O.bodies.insertAtId after the scene was split (at its first step under mpirun) or in a "
                               "scene holding a packing read in slabs")
        if id < len(self):
            raise ValueError(f"O.bodies.insertAtId: id {id} is taken (by a body or an erased one, whose ids Talus does "
                             f"not reuse); the next free id is {len(self)}")
        if not isinstance(spec, BodySpec):
            raise TypeError(f"O.bodies.insertAtId: takes a body (utils.sphere(...), ...), got {spec!r}")
        for hole in self.append([sphere((0, 0, 0), 1) for _ in range(id - len(self))]):
            self.erase(hole)
        return self.append(spec)

    def _append_specs(self, specs: list[BodySpec], ids: Iterable[int] | None = None) -> list[int]:
        """Append ``specs`` (as bodies ``ids`` of this process's slab of a packing, when given)."""
        # Room for all of them at once: the per-body tables grown body by body would be copied
        # at each one (a scene of N bodies built in N^2 time).
        count = self._scene._cpp.bodyCount() + len(specs)
        self._scene._appearance.ensure(count)
        self._scene._reference.ensure(count)
        if ids is None:
            return [self._add(s) for s in specs]
        if all(s.kind == "Sphere" and s._scene is None and s.group_mask == 1 and s.initial.keys() <= {"highlight", "wire"}
               for s in specs):
            return self._append_plain_spheres(specs, ids)
        return [self._add(s, id) for s, id in zip(specs, ids)]

    def _append_plain_spheres(self, specs: list[BodySpec], ids: Iterable[int]) -> list[int]:
        """What ``_add`` does for each of ``specs``, spheres that set nothing but their centre,
        radius, material, colour, look and fixedness (a slab of a sphere file: millions of them),
        with the per-row tables written once for all (reference state: as made)."""
        scene = self._scene
        scene._views.before_adding(scene._cpp, len(specs))
        materials = {}
        rows = []
        for spec in specs:
            key = spec.material if isinstance(spec.material, (int, str, type(None))) else id(spec.material)
            if key not in materials:
                materials[key] = scene.materials.resolve(-1 if spec.material is None else spec.material)
            rows.append(self._create(spec, materials[key]))
        added = [distributed.added(scene, row, id) for row, id in zip(rows, ids)]
        rows = np.asarray(rows)
        scene._reference.pos[rows] = scene._cpp.pos()[rows]     # new spheres: not rotated, refOri as made
        look = scene._appearance
        look.color[rows] = [spec.color for spec in specs]
        look.highlight[rows] = [spec.initial.get("highlight", False) for spec in specs]
        look.wire[rows] = [spec.initial.get("wire", False) for spec in specs]
        for spec, id in zip(specs, added):
            spec.id, spec._scene = id, scene
        return added

    def _add(self, spec: BodySpec, slab_id: int | None = None) -> int:
        if spec._scene is not None:
            raise ValueError(f"this body is already body {spec.id} of a scene; make another one to append")
        scene = self._scene
        scene._views.before_adding(scene._cpp)
        row = self._create(spec, scene.materials.resolve(-1 if spec.material is None else spec.material))
        id = distributed.added(scene, row, slab_id)     # the row, unless the scene is built in slabs
        if spec.group_mask != 1:
            scene.bodies[id].mask = spec.group_mask
        state = scene.bodies[id].state
        state.refPos, state.refOri = state.pos, state.ori     # Yade's reference: as made
        for name, value in spec.initial.items():
            if name in ("highlight", "wire"):
                continue
            setattr(state, name, value)
        look = scene._appearance
        look.ensure(scene._cpp.bodyCount())
        look.color[row] = spec.color
        look.highlight[row] = spec.initial.get("highlight", False)
        look.wire[row] = spec.initial.get("wire", False)
        spec.id, spec._scene = id, scene
        return id

    def _create(self, spec: BodySpec, material: int) -> int:
        try:
            add = shape_kind(spec.kind).add
        except KeyError:
            add = None
        if add is None:
            raise ValueError(f"O.bodies.append: a body without a shape Talus can add ({spec.kind or 'none'}): give "
                             "it one (b.shape = Sphere(radius=r)), or make it with utils.sphere, facet, box, wall")
        return add(self._scene, spec, material)

    def appendClumped(self, specs: Iterable[BodySpec], discretization: int = 0) -> tuple[int, list[int]]:
        """Add bodies (spheres, facets, boxes) and make them one clump (Yade's appendClumped);
        returns (clump id, member ids). Mass and inertia as :meth:`clump`."""
        specs = list(specs)
        scene = self._scene
        if not scene.periodic:
            ids = self.append(specs)
            return self.clump(ids, discretization), ids
        # In a periodic cell members may stick out of it, only the clump's centre must be inside:
        # the members are added with the cell's check off, the clump's centre checked after (on
        # failure everything added is removed again).
        scene._cpp.setPeriodic(False)
        ids, clump = [], None
        try:
            for spec in specs:
                ids.append(self._add(spec))
            clump = self.clump(ids, discretization)
            scene._cpp.setPeriodic(True)
        except ValueError as e:
            if clump is not None:
                self.erase(clump, eraseClumpMembers=True)
            else:
                for i in ids:
                    self.erase(i)
            scene._cpp.setPeriodic(True)
            raise ValueError(f"appendClumped: {e}") from None
        return clump, ids

    def clump(self, ids: Iterable[int], discretization: int = 0) -> int:
        """Make existing bodies (spheres, facets, boxes) one clump (Yade's O.bodies.clump);
        returns its id. A member of another clump leaves it. Mass and inertia as Yade's: the
        members summed whole (a sphere from its material's density), or, with
        ``discretization`` > 0 and overlapping spheres, the spheres' union integrated on a grid
        of cubes of edge (shortest side of their bounding box) / discretization."""
        scene = self._scene
        if distributed.is_split(scene):
            self._whole_scene("O.bodies.clump")
        rows = [int(i) for i in ids]
        if isinstance(distributed.domain(scene), distributed.HeldRows):     # a scene read in slabs: ids to rows
            rows = [distributed.clumpable_row(scene, i) for i in rows]
        scene._views.before_adding(scene._cpp)
        return distributed.added(scene, int(_dem.add_clump(scene._cpp, rows, int(discretization))))

    def addToClump(self, bids, cid: int, discretization: int = 0) -> None:
        """Yade's addToClump (talus.dem.core.clumps.addToClump)."""
        self._whole_scene("O.bodies.addToClump")
        clumps.addToClump(self, bids, cid, discretization)

    def releaseFromClump(self, bid: int, cid: int, discretization: int = 0) -> None:
        """Yade's releaseFromClump (talus.dem.core.clumps.releaseFromClump)."""
        self._whole_scene("O.bodies.releaseFromClump")
        clumps.releaseFromClump(self, bid, cid, discretization)

    def replaceByClumps(self, ctList, amounts, discretization: int = 0, seed: int | None = None) -> list:
        """Yade's replaceByClumps (talus.dem.core.clumps.replaceByClumps)."""
        self._whole_scene("O.bodies.replaceByClumps")
        return clumps.replaceByClumps(self, ctList, amounts, discretization, seed)

    def _whole_scene(self, what: str) -> None:
        """Refuse ``what`` under mpirun once the scene is split or while it holds a slab of a
        packing: it names bodies by the rows of a whole scene."""
        if distributed.domain(self._scene) is not None:
            distributed.refuse(f"{what} after the scene was split (at its first step under mpirun) or in a scene "
                               f"holding a packing read in slabs")

    def getRoundness(self, excludeList=()) -> float:
        """Yade's roundness coefficient (talus.dem.core.clumps.getRoundness)."""
        return clumps.getRoundness(self, excludeList)

    def erase(self, id: int, eraseClumpMembers: bool = False) -> bool:
        """Remove a body and its contacts (its id is not reused); False if it was already
        erased (Yade's). Erasing a clump frees its members unless ``eraseClumpMembers``; erasing
        a member takes it out of its clump, which keeps its mass and inertia (as in Yade) and
        goes with its last member."""
        if distributed.domain(self._scene) is not None:     # under mpirun: every process erases its copy
            return distributed.erase(self._scene, int(id) + len(self) if id < 0 else int(id), bool(eraseClumpMembers))
        if self[id] is None:
            return False
        _dem.erase(self._scene._cpp, int(id), bool(eraseClumpMembers))
        return True

    def clear(self) -> None:
        """Remove every body and its contacts; the next body appended gets id 0 (Yade's
        O.bodies.clear, which also leaves the old contacts in O.interactions: Talus removes them).
        Per-body arrays taken before (positions(), ...) no longer follow the bodies."""
        scene = self._scene
        if isinstance(distributed.domain(scene), distributed.HeldRows):    # no slab left
            scene._domain = None
        scene._cpp.clearBodies()
        scene._views.forget()
        scene._appearance = Appearance()
        scene._reference = ReferenceStates()

    def replace(self, specs: BodySpec | Iterable[BodySpec]):
        """Remove every body, then append ``specs`` (Yade's O.bodies.replace); returns their ids,
        which start at 0."""
        specs = [specs] if isinstance(specs, BodySpec) else list(specs)
        for spec in specs:
            if not isinstance(spec, BodySpec):
                raise TypeError(f"O.bodies.replace: takes bodies (utils.sphere(...), ...), got {spec!r}")
        self.clear()
        return self.append(specs)

    def __getitem__(self, id: int) -> Body | None:
        """Body ``id`` (negative: counted from the end), None if it was erased (Yade's)."""
        if type(id) is not int and not isinstance(id, (int, np.integer)):
            raise TypeError(f"body ids are integers, got {id!r}")
        scene = self._scene
        split = distributed.domain(scene)
        if split is None:   # scripts call this for one body at a time in their loops: one call to the core
            row = _dem.body_row(scene._cpp, id)
            return None if row < 0 else self._view(row)
        n = split.globalCount
        i = int(id) + n if id < 0 else int(id)
        if not 0 <= i < n:
            raise IndexError(f"no body with id {int(id)} (ids run from 0 to {n - 1})")
        if distributed.is_split(scene):     # collective: a body owned elsewhere as a snapshot
            from talus.dem.split import by_id
            return by_id.body(scene, i, lambda row, id: Body(scene, row, id))
        row = distributed.row_of(scene, i)     # a scene holding a slab of a packing: the bodies held here
        if row is None or not scene._cpp.alive()[row]:
            return None
        return Body(scene, row, i)

    def _here(self, id: int) -> Body | None:
        """Body ``id`` as this process holds it (owned, or a wall, facet or box), without the
        collective read ``O.bodies[id]`` is under mpirun: for code going over this process's own
        bodies (the exporters); None if it was erased."""
        if not distributed.is_split(self._scene):
            return self[id]
        row = distributed.row_of(self._scene, int(id))     # (raises for a body owned elsewhere)
        return None if row is None or not self._scene._cpp.alive()[row] else Body(self._scene, row, int(id))

    def _view(self, row: int) -> Body:
        """The body in ``row`` of a scene in one process, made once per row: a view holds its row
        only, so it stays right whichever body the row holds, and ``O.bodies[i] is O.bodies[i]``
        as in Yade."""
        views = self._views
        if row >= len(views):
            views.extend([None] * (row + 1 - len(views)))
        body = views[row]
        if body is None:
            body = views[row] = Body(self._scene, row)
        return body

    def gather(self, ids: Iterable[int]) -> list:
        """Snapshots of the bodies ``ids`` (talus.dem.core.gathered: ``id``, ``dynamic``,
        ``radius``, ``state.pos``, ``vel``, ``angVel``, ``ori``, ``mass``, ``inertia``), in that
        order, whichever process owns them. Under mpirun it is collective: every process calls it
        with the same ids and gets the same snapshots. A negative id counts from the end; an
        erased body is an error naming it."""
        from talus.dem.core import gathered
        n = len(self)
        wanted = []
        for id in ids:
            if not isinstance(id, (int, np.integer)):
                raise TypeError(f"O.bodies.gather: body ids are integers, got {id!r}")
            wanted.append(int(id) + n if id < 0 else int(id))
        split = distributed.domain(self._scene)
        if split is not None:   # ids out of range and erased bodies are refused on every process alike
            return gathered.from_table(wanted, split.gather(self._scene._cpp, wanted))
        for i in wanted:
            if not 0 <= i < n:
                raise IndexError(f"O.bodies.gather: no body with id {i} (ids run from 0 to {n - 1})")
        bodies = [self[i] for i in wanted]
        for i, b in zip(wanted, bodies):
            if b is None:
                raise ValueError(f"O.bodies.gather: body {i} was erased")
        return [gathered.of_body(b) for b in bodies]

    def __len__(self) -> int:
        split = distributed.domain(self._scene)
        return self._scene._cpp.bodyCount() if split is None else split.globalCount

    def __iter__(self):
        if distributed.is_split(self._scene):   # collective: every body, owned elsewhere as a snapshot
            from talus.dem.split import bodies as split_bodies, by_id
            by_id.agree(by_id.LOOP)     # every process is here (a read by id made by some only is named)
            return split_bodies.every_body(self._scene, lambda row, id: Body(self._scene, row, id))
        if distributed.domain(self._scene) is not None:
            distributed.refuse("iterating over O.bodies before the first step of a scene holding a packing read in "
                               "slabs (each process holds its own slab until the split)")
        alive = self._scene._cpp.alive()
        return (self._view(i) for i in range(len(self)) if alive[i])
