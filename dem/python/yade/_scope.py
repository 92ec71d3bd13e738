"""Which of Yade's names and example scripts are outside Talus's scope, and why.

Talus implements Yade's DEM core, its pore-flow, VANS, FEM x DEM and OpenFOAM couplings, and the
potential particles and blocks. What needs other physics is out of scope: each rule below names
it. A rule's pattern is searched both in a script's text (cases/yade_examples.py) and in a bare
Yade name (the error for a name Talus lacks), so patterns match either form.
"""
from __future__ import annotations

import re

from yade._yade_names import NAMES

RULES: list[tuple[str, str]] = [
    (r"Polyhedra|polyhedra_utils", "polyhedra"),
    (r"LBM", "lattice Boltzmann fluid"),
    (r"\bSPH\b|SPHEngine|_SPH|SPH_", "smoothed-particle hydrodynamics"),
    (r"LevelSet|FastMarchingMethod", "level-set shapes"),
    (r"Tetra|DeformableElement|deformableelementsutils|DeformableCohesive|\bNode\b|_Node_|InternalForce|LinIsoElastMat|"
     r"LinIsoRayleighDampElastMat|LinCohesive", "tetrahedra and deformable elements"),
    # ThermalEngine has conduction, the pore fluid and thermal expansion; the state class is not a
    # Talus one (the engine holds every body's thermal fields)
    (r"ThermalState", "Yade's ThermalState class (Talus's ThermalEngine holds the thermal fields; planned)"),
    # TwoPhaseFlowEngine has its clusters (PhaseCluster, clusterOutvadePore) but not the
    # invasion of a pore out of a cluster
    (r"clusterInvadePore", "invading a pore out of a two-phase cluster (TwoPhaseFlowEngine's clusterInvadePore; planned)"),
    (r"Cpm", "concrete (CPM) model"),
    (r"WireMat|WirePhys|WireState", "wire mesh model"),
    (r"L6Geom|L3Geom", "local-coordinates contact geometry (L3Geom/L6Geom)"),
    (r"Bubble", "bubble model"),
    # (not TwoPhaseFlowEngine's computeCapillaryForce: the forces of its phase pressures)
    (r"(?<!compute)Capillar|ViscElCap|MeasureCapStress|Law2_ScGeom_CapillaryPhys|MeniscusPhysicalDataFactory", "capillary bridges"),
    (r"GridNode|GridConnection|GridCoGrid|PFacet|gridpfacet", "grid and PFacet elements"),
    (r"ChainedCylinder|\bCylinder\b|_Cylinder|Cylinder_|\bcylinder(\(|$)", "cylinders"),
    (r"Tori|Torus", "tori"),
    (r"JCFpm", "jointed cohesive-frictional model"),
    (r"Luding", "Luding's model"),
    (r"Mortar", "mortar model"),
    (r"\bmpy\b|^mpy$|Subdomain|MPIBodyContainer|FluidDomainBbox|domaindecomposition|bisectionDecomposition", "MPI subdomains (scripts for Yade's mpy run under mpirun, cases/dem/dem_mpy_examples.py; mpy's Subdomain and "
     "decomposition modules are not Talus's: Zoltan partitions)"),
    (r"hdaps", "laptop accelerometer input (/sys/devices/platform/hdaps)"),
    (r"LubricationPhys|Law2_ScGeom_ImplicitLubricationPhys|LubricationPDFEngine", "lubrication contact law"),
    (r"HertzMindlinExtended|Law2_ScGeom_MindlinPhys_HertzWithLinearShear|FrictMatCDM|CDMPhys|_CDM",
     "extended Hertz-Mindlin laws and the conical damage model"),
    (r"Clump.*[Bb]reak|clumps-breakage", "breakable clumps"),
    (r"Inelastic|InelastCohFrict", "inelastic cohesive-frictional model"),
    (r"PartialSat", "partially saturated clay model"),
    (r"NormalInelastic", "normal inelasticity model"),
    (r"KinemC|KinemSimpleShearBox|SimpleShear\b", "Yade's shear-box kinematic controllers"),
    (r"Ig2_Sphere_Polyhedra|PotentialParticle2AABB", "polyhedra"),
    (r"urlretrieve|urlopen|\bwget\b|requests\.get", "input from the network"),
]


def out_of_scope(text: str) -> str | None:
    """The reason a script's text or a Yade name is out of Talus's scope, or None."""
    for pattern, reason in RULES:
        if re.search(pattern, text):
            return reason
    return None


def missing_name_note(name: str, module: str | None = None) -> str | None:
    """What to say when ``name`` is not found in Talus's ``module`` (None: in a script's namespace,
    which holds yade's, yade.utils' and yade.pack's names): None unless it is one of Yade
    2023.02a's own names there."""
    modules = [module] if module else ["yade", "yade.utils", "yade.pack"]
    if module == "yade":
        modules.append("modules")       # `from yade import mpy`
    if not any(name in NAMES.get(m, ()) for m in [*modules, "yade"]):
        return None
    reason = out_of_scope(name)
    where = f"{module}.{name}" if module not in (None, "yade") else name
    if reason and reason.endswith("; planned)"):
        return f"{where} is a name of Yade 2023.02a that Talus does not implement yet: it belongs to {reason}"
    if reason:
        return (f"{where} is a name of Yade 2023.02a that Talus does not implement: it belongs to {reason}, "
                f"which is outside Talus's scope (docs/yade-scripts.md)")
    return (f"{where} is a name of Yade 2023.02a that Talus does not implement yet; it is within Talus's "
            f"scope: please report it")


def module_getattr(module: str):
    """A module ``__getattr__`` for Yade's module ``module``: a Yade name Talus lacks gets an
    AttributeError saying so (and whether it is out of scope) instead of Python's bare one."""
    def __getattr__(name: str):
        raise AttributeError(missing_name_note(name, module) or f"module {module!r} has no attribute {name!r}")
    return __getattr__
