"""Reliability case: a checkpoint's size grows with the real contacts, not with the candidate pairs.

Run:      build/bin/talus run cases/reliability_checkpoint_size.py [--quick] [--results DIR]
Set-up:   spheres (radius 5 mm +- 20 %) rained into a box of walls under gravity with
          Hertz-Mindlin contacts (the law whose per-contact state is the largest) until the bed
          settles; quick: 2 000 spheres, 25 000 steps; full: 6 000 spheres, 40 000 steps.
Checked:  reliability.checkpoint-bytes-per-contact: (size of the bed's checkpoint - size of the
          same scene's checkpoint without contacts) / number of real contacts. A real contact is
          232 bytes of Contact fields and 255 of Hertz-Mindlin state (ContactExtra) in the file:
          <= 600 bytes. Checkpoints of format 7 stored every candidate pair inside the
          collider's skin as well, several times more rows than contacts in a bed, and hundreds
          of times more in a loose scene.
Produces: the record, with the file sizes, the real contacts and the candidate pairs.
"""
import os
import tempfile

from talus import results
from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom,
                       Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                       Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, NewtonIntegrator,
                       PWaveTimeStep, Scene, wall)
from talus.dem.packing import pack


def settled_bed(spheres: int, steps: int) -> Scene:
    S = Scene()
    S.materials.append(FrictMat(young=5e7, poisson=0.3, density=2600, frictionAngle=0.5))
    side = 0.2
    S.bodies.append([wall(0, 2, 1), wall(0, 0), wall(side, 0), wall(0, 1), wall(side, 1)])
    sp = pack.SpherePack()
    sp.makeCloud((0, 0, 0), (side, side, spheres * 2.5e-5), rMean=0.005, rRelFuzz=0.2, num=spheres, seed=3)
    sp.toSimulation(S)
    S.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_MindlinPhys(betan=0.3, betas=0.3)],
                                 [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.3)]
    S.dt = 0.7 * PWaveTimeStep(S)
    S.run(steps)
    return S


def main():
    args = results.case_arguments(__doc__).parse_args()
    case = results.Case("reliability.checkpoint-bytes-per-contact", quick=args.quick, folder=args.results)
    spheres, steps = (2000, 25000) if args.quick else (6000, 40000)
    S = settled_bed(spheres, steps)
    real, pairs = S.interactions.countReal(), len(S.interactions)
    with tempfile.TemporaryDirectory() as folder:
        bed, bare = os.path.join(folder, "bed.h5"), os.path.join(folder, "bare.h5")
        S.save(bed)
        S.interactions.clear()
        S.save(bare)
        with_contacts, without = os.path.getsize(bed), os.path.getsize(bare)
    per_contact = (with_contacts - without) / real
    print(f"{spheres} spheres, {real} real contacts among {pairs} candidate pairs: checkpoint "
          f"{with_contacts / 1e6:.2f} MB, {without / 1e6:.2f} MB without contacts, {per_contact:.0f} bytes per contact")
    case.record("bytes of checkpoint per real contact (Hertz-Mindlin, settled bed)", per_contact,
                "232 bytes of contact fields + 255 of Hertz-Mindlin state per stored row", 600.0,
                spheres=spheres, real_contacts=real, candidate_pairs=pairs, file_bytes=with_contacts,
                file_bytes_without_contacts=without)


if __name__ == "__main__":
    main()
