"""Labels of engines, functors and sub-engines become names of Python's builtins, as in Yade
2023.02a (where a test module, not only the script, sees them)."""
import builtins

from talus.dem import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom, InsertionSortCollider,
                       InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                       NewtonIntegrator, RotationEngine, Scene, TranslationEngine)


def test_labels_of_engines_functors_and_parts_are_builtins():
    scene = Scene()
    bo1 = Bo1_Sphere_Aabb(label="t_lbl_bo1")
    law = Law2_ScGeom_FrictPhys_CundallStrack(label="t_lbl_law")
    trans, rot = TranslationEngine(label="t_lbl_trans"), RotationEngine(label="t_lbl_rot")
    comb = trans + rot
    comb.label = "t_lbl_comb"
    scene.engines = [ForceResetter(label="t_lbl_reset"), InsertionSortCollider([bo1]),
                     InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [law]),
                     comb, NewtonIntegrator()]
    try:
        assert builtins.t_lbl_reset is scene.engines[0]
        assert builtins.t_lbl_bo1 is bo1 and builtins.t_lbl_law is law
        assert builtins.t_lbl_trans is trans and builtins.t_lbl_rot is rot and builtins.t_lbl_comb is comb
        scene.engines = [ForceResetter()]
        assert builtins.t_lbl_reset is not None          # Yade keeps them when the engines change
    finally:
        for name in [n for n in vars(builtins) if n.startswith("t_lbl_")]:
            delattr(builtins, name)
