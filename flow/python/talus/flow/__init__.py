"""Fluid models on the DEM core (Yade's HydroForceEngine and FlowEngine families).

Available now: the pore-scale flow ``FlowEngine`` (Yade's FlowEngine, ``talus.flow.pore``), its
periodic variant ``PeriodicFlowEngine`` (``talus.flow.periodic``), heat conduction between
particles ``ThermalEngine`` (Yade's, ``talus.flow.thermal``), quasi-static two-phase flow
``TwoPhaseFlowEngine`` (Yade's, ``talus.flow.twophase``) and
the 1D vertical VANS fluid resolution (``VansFluid``, the fluid part of Yade's
``HydroForceEngine``; see ``talus.flow.vans`` and ``docs/flow.md``)::

    from talus.flow import VansFluid, slope_gravity
    fluid = VansFluid(nCell=200, deltaZ=1e-3, gravity=slope_gravity(0.05), ilm=0, iturbu=1)
    fluid.fluidResolution(10.0, 1e-2)
    print(fluid.vxFluid)
"""

from talus.flow import hydro, stray_attributes
from talus.flow.coupling import VansCoupling
from talus.flow.hydro import HydroForceEngine, averageProfile
from talus.flow.pore import FlowEngine, HiddenSphereWarning
from talus.flow.periodic import PeriodicFlowEngine
from talus.flow.phasecluster import PhaseCluster
from talus.flow.thermal import ThermalEngine
from talus.flow.twophase import TwoPhaseFlowEngine, UnsaturatedEngine
from talus.flow.vans import EffectiveViscosity, MixingLength, TopBoundary, VansFluid, slope_gravity

__all__ = ["FlowEngine", "PeriodicFlowEngine", "ThermalEngine", "TwoPhaseFlowEngine", "UnsaturatedEngine", "PhaseCluster", "HiddenSphereWarning", "HydroForceEngine", "averageProfile", "VansCoupling", "VansFluid",
           "MixingLength", "EffectiveViscosity", "TopBoundary", "slope_gravity"]


def yade_run_defaults() -> None:
    """Behave as Yade 2023.02a in a Yade script's run (yade.yade_run_defaults calls it): particles
    leaving the VANS grid get no fluid force (talus.flow.hydro), and an attribute an engine does
    not have is kept with a warning instead of refused (talus.flow.stray_attributes)."""
    hydro.yade_run_defaults()
    stray_attributes.accept()
