"""What the benchmark scenes of this folder share, importable by the same text under Yade
(`yade -x`) and Talus (`talus run`): reading the packing a case wrote, the frictional bodies, the
periodic scenes and timing the steps. Yade's names come from the `yade` module, which is Yade's
own under `yade -x` and Talus's namespace of Yade's names under `talus run`.

A packing file: a first line of numbers (the scene's parameters), then one line per sphere
`x y z r`, or, in files that also hold a mesh, `S x y z r` and `F x1 y1 z1 x2 y2 z2 x3 y3 z3` per
triangle."""
import time


def read_packing(path):
    """(parameters, spheres, triangles): the first line's numbers, each sphere's (x, y, z, r)
    and each triangle's nine coordinates."""
    spheres, triangles = [], []
    with open(path) as source:
        parameters = [float(v) for v in source.readline().split()]
        for line in source:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "F":
                triangles.append([float(v) for v in fields[1:]])
            else:
                spheres.append(tuple(float(v) for v in (fields[1:] if fields[0] == "S" else fields)))
    return parameters, spheres, triangles


def frictional_bodies(O, young, density, spheres, triangles=()):
    """The scenes' one FrictMat (poisson 0.3, friction 0.5 rad) and the bodies made of it: the
    facets of `triangles` and the `spheres`. Returns (facet ids, sphere ids)."""
    from yade import FrictMat, utils
    material = O.materials.append(FrictMat(young=young, poisson=0.3, frictionAngle=0.5, density=density))
    facets = O.bodies.append([utils.facet((t[0:3], t[3:6], t[6:9]), material=material) for t in triangles])
    return facets, O.bodies.append([utils.sphere((x, y, z), r, material=material) for x, y, z, r in spheres])


def walled_bed(O, material, box_x, box_y):
    """The dense bed's box and engines (cases 11 and the MPI beds): five walls of `material` (the
    floor at z = 0, the sides at 0 and `box_x`, `box_y`), linear Cundall-Strack with Coulomb
    friction, Cundall damping 0.2, gravity."""
    import yade
    from yade import utils
    O.bodies.append([utils.wall(0, axis=2, sense=1, material=material), utils.wall(0, axis=0, sense=1, material=material),
                     utils.wall(box_x, axis=0, sense=-1, material=material),
                     utils.wall(0, axis=1, sense=1, material=material),
                     utils.wall(box_y, axis=1, sense=-1, material=material)])
    O.engines = [
        yade.ForceResetter(),
        yade.InsertionSortCollider([yade.Bo1_Sphere_Aabb(), yade.Bo1_Wall_Aabb()]),
        yade.InteractionLoop([yade.Ig2_Sphere_Sphere_ScGeom(), yade.Ig2_Wall_Sphere_ScGeom()],
                             [yade.Ip2_FrictMat_FrictMat_FrictPhys()], [yade.Law2_ScGeom_FrictPhys_CundallStrack()]),
        yade.NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
    ]


def periodic_linear(O, sides, young, density, spheres, controllers=()):
    """The periodic scenes: a cell of `sides`, the spheres (frictional_bodies), linear
    Cundall-Strack with Coulomb friction, the `controllers`, Cundall damping 0.2, no gravity."""
    import yade
    O.periodic = True
    O.cell.setBox(*sides)
    frictional_bodies(O, young, density, spheres)
    O.engines = [
        yade.ForceResetter(),
        yade.InsertionSortCollider([yade.Bo1_Sphere_Aabb()]),
        yade.InteractionLoop([yade.Ig2_Sphere_Sphere_ScGeom()], [yade.Ip2_FrictMat_FrictMat_FrictPhys()],
                             [yade.Law2_ScGeom_FrictPhys_CundallStrack()]),
        *controllers,
        yade.NewtonIntegrator(damping=0.2),
    ]


def real_contacts(O):
    return sum(1 for i in O.interactions if i.isReal) if hasattr(O, "interactions") else O._cpp.realContactCount()


def timed(O, steps, run=None, figure=real_contacts):
    """One step to build the contacts, then `run()` (default: O.run(steps)) timed; prints
    `TIMED <steps> <seconds> <figure(O)> <cpu seconds>` and, in Talus, ` fused <fused steps>`."""
    O.run(1, True)
    start, cpu = time.perf_counter(), time.process_time()
    if run is None:
        O.run(steps, True)
    else:
        run()
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
    fused = f" fused {O.fusedSteps}" if hasattr(O, "fusedSteps") else ""
    print(f"TIMED {steps} {seconds:.6f} {figure(O)} {cpu:.6f}{fused}")


def write_spheres(O, path, ids):
    """Spheres `ids` where they are now, as `S x y z r` lines (the fill a settling run leaves)."""
    with open(path, "w") as out:
        out.writelines(f"S {' '.join(repr(float(v)) for v in (*O.bodies[i].state.pos, O.bodies[i].shape.radius))}\n"
                       for i in ids)
