"""The DEM core from Python, with Yade's vocabulary.

    from talus.dem import *
    O.bodies.append([sphere((0, 0, 1), 0.1), wall(0, axis=2)])
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=0)]
    O.dt = 0.5 * PWaveTimeStep()
    O.run(1000, True)

``O`` is the default scene; ``Scene()`` makes another.
"""

from talus import plot
from talus.dem.geometry import geom
from talus.dem.packing import pack
from talus.dem.analysis import progress, timing
from talus.dem.files import ymport
from talus.dem.core.bodies import Body, BodySpec, aabbWalls, box, facet, sphere, wall
from talus.dem.geometry.shapes import Box, Clump, Facet, Shape, Sphere, Wall
from talus.dem.geometry.blocks import *  # noqa: F401,F403  (Potential Blocks, Yade's names)
from talus.dem.geometry.blocks import __all__ as _block_names
from talus.dem.geometry.particles import *  # noqa: F401,F403  (Potential Particles, Yade's names)
from talus.dem.geometry.particles import __all__ as _particle_names
from talus.dem.geometry.blockgen import Joint, JointFileError, generateBlocks, readJoints
from talus.dem.step.engines import *  # noqa: F401,F403  (Yade's engine and functor names)
from talus.dem.step.engines import __all__ as _engine_names
from talus.dem.base.linalg import (Matrix3, Matrix6, Quaternion, Vector2, Vector2i, Vector3, Vector3i, Vector4,
                              Vector6, Vector6i)
from talus.dem.control.controllers import PeriIsoCompressor
from talus.dem.control.controllers import (GlobalStiffnessTimeStepper, PeriTriaxController, RayleighWaveTimeStep,
                                   TriaxialStressController, growParticles, setContactFriction)
from talus.dem.analysis.energy import EnergyTracker
from talus.dem.control.triaxial import ThreeDTriaxialEngine, TriaxialCompressionEngine, TriaxialStateRecorder
from talus.dem.step.legacy import *  # noqa: F401,F403  (Yade's older names of the interaction loop)
from talus.dem.step.legacy import __all__ as _legacy_names
from talus.dem.control.preprocessors import TriaxialTest
from talus.dem.files.export import VTKExporter, VTKRecorder
from talus.dem.step.kinematic import *  # noqa: F401,F403  (Yade's kinematic engines)
from talus.dem.step.kinematic import __all__ as _kinematic_names
from talus.dem.step.force_engines import *  # noqa: F401,F403  (Yade's force engines, interaction callbacks)
from talus.dem.step.force_engines import __all__ as _force_engine_names
from talus.dem.packing.factories import BoxFactory, CircularFactory, SpheresFactory
from talus.dem.step.domain_limiter import DomainLimiter
from talus.dem.packing.reset_random_position import ResetRandomPosition
from talus.dem.control.servo import ServoPIDController
from talus.dem.control.peri3d import Peri3dController
from talus.dem.core.interactions import Interaction
from talus.dem.files.io import CheckpointError
from talus.dem.core.materials import CohFrictMat, ElastMat, FrictMat, Material, ViscElMat
from talus.dem.analysis.measure import (avgNumInteractions, bodyStressTensors, fabricTensor, getStress, getStressAndTangent,
                               porosity, unbalancedForce)
from talus.dem.core.scene import PWaveTimeStep, Scene, contactTimeStep
from talus.dem.core.scenes import set_default_scene

O = Scene()
set_default_scene(O)

__all__ = ["O", "Scene", "Body", "BodySpec", "Shape", "Sphere", "Wall", "Facet", "Box", "Clump", "sphere", "wall", "facet", "box", "geom", "pack", "timing", "ymport", "Material",
           "ElastMat", "FrictMat", "ViscElMat", "CohFrictMat", "PWaveTimeStep", "contactTimeStep", "Vector2", "Vector2i", "Vector3", "Vector3i", "Vector4", "Vector6",
           "Vector6i", "Matrix3", "Matrix6", "Quaternion",
           "unbalancedForce", "getStress", "getStressAndTangent", "avgNumInteractions", "fabricTensor", "bodyStressTensors",
           "porosity",
           "VTKRecorder", "VTKExporter", "CheckpointError", "Interaction", "progress", "plot", "EnergyTracker",
           "GlobalStiffnessTimeStepper", "PeriTriaxController", "PeriIsoCompressor", "TriaxialStressController", "RayleighWaveTimeStep",
           "growParticles", "setContactFriction", "aabbWalls",
           "TriaxialCompressionEngine", "ThreeDTriaxialEngine", "TriaxialStateRecorder", *_legacy_names, "TriaxialTest",
           *_kinematic_names, *_force_engine_names, "SpheresFactory", "BoxFactory", "CircularFactory", "DomainLimiter",
           "ResetRandomPosition", "ServoPIDController", "Peri3dController",
           *_engine_names, *_block_names, *_particle_names, "Joint", "JointFileError", "generateBlocks", "readJoints"]
