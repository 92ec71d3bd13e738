/*---------------------------------------------------------------------------*\
Application
    talusPointForceFoam

Description
    Transient incompressible laminar PISO solver (as icoFoam) coupled with the Talus DEM by
    point forces: each fluid step it receives the particles from the DEM process, locates each
    particle's cell on this rank's sub-mesh (walk from the previous cell, octree as fallback),
    returns the drag V_p K (u_f - u_p), u_f the velocity of the particle's cell, plus the
    buoyancy -rho V_p g of each particle, and adds the drag's reaction as an explicit momentum
    source in the particle's cell. K is the closure of dragModel (dragClosure.H, fluid fraction
    1): by default Stokes, 3 pi mu d (u_f - u_p) as Yade's icoFoamYade, or SchillerNaumann for
    finite particle Reynolds numbers.

    Started by the DEM side (talus.coupling.FoamCoupling) with MPI_Comm_spawn; serial, or with
    -parallel on a decomposed case. Message protocol: coupling/FoamProtocol.h.

    Case files as icoFoam (0/U, 0/p, system/fvSolution PISO) plus
        constant/transportProperties  nu [m2/s] and rho [kg/m3]
        constant/g                    gravity, compared with the DEM side's
        constant/couplingProperties   optional: dragModel Stokes | SchillerNaumann | DiFelice |
                                      ErgunWenYu (default Stokes)

License
    GPL-3.0-or-later, like OpenFOAM.
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "dragClosure.H"

#include "fvCFD.H"
#include "pisoControl.H"
#include "uniformDimensionedFields.H"

#include <cstdio>

namespace proto = talus::foam_protocol;

static const char* const solverName = "talusPointForceFoam";
// The drag closure without a dragModel entry: Stokes, as Yade's icoFoamYade.
static const char* const defaultDragModel = "Stokes";


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Incompressible PISO solver coupled with the Talus DEM by point forces"
        " (started by talus.coupling.FoamCoupling)"
    );
    argList::addOption
    (
        "couplingTimeout",
        "seconds",
        "Longest wait for the DEM process before aborting every process (default 60)"
    );

    #include "setRootCaseLists.H"

    #include "startDemLink.H"

    #include "createTime.H"
    #include "createMesh.H"

    pisoControl piso(mesh);

    #include "createFields.H"
    #include "initContinuityErrs.H"

    // A particle concerns the rank whose cell holds it only.
    const scalar couplingMargin = 0;
    #include "answerDemHandshake.H"

    const vector gravity = g.value();

    talusFoam::ParticleLocator locator(mesh);
    talusFoam::ExchangeTimer exchangeTimer;
    talusFoam::ParticleInbox inbox(link);
    std::vector<double> particles;    // per particle x y z vx vy vz r index
    std::vector<double> reply;        // header (FoamProtocol.h), then per particle fx fy fz owned beta uf
    // Per particle the drag closure's inputs (fluid fraction 1, slip speed, diameter) and its K.
    std::vector<double> dragAlpha, dragSlip, dragDiameter, dragK;

    Info<< "\nStarting the coupled time loop (drag " << drag.name() << ")\n" << endl;

    while (true)
    {
        #include "receiveParticles.H"
        runTime++;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        locator.locate(particles, n, halo);

        reply.assign(proto::kReplyHeader + proto::kForceDoubles*n, 0.0);
        S.primitiveFieldRef() = Zero;
        // The drag's K of every particle first, in one call (dragClosure.H); a particle this
        // rank does not own gets one too, unused.
        dragAlpha.assign(n, 1.0);
        dragSlip.resize(n);
        dragDiameter.resize(n);
        dragK.resize(n);
        scalar maxRe = 0;
        for (label i = 0; i < n; ++i)
        {
            const double* q = &particles[proto::kParticleDoubles*i];
            dragDiameter[i] = 2*q[6];
            dragSlip[i] =
                locator.owned(i) ? mag(U[locator.cell(i)] - vector(q[3], q[4], q[5])) : 0;
            maxRe = max(maxRe, dragSlip[i]*dragDiameter[i]/nu.value());
        }
        drag.K(n, dragAlpha.data(), dragSlip.data(), dragDiameter.data(), dragK.data());
        for (label i = 0; i < n; ++i)
        {
            if (!locator.owned(i))
            {
                continue;
            }
            const double* q = &particles[proto::kParticleDoubles*i];
            const vector up(q[3], q[4], q[5]);
            const scalar volume = (4.0/3.0)*constant::mathematical::pi*pow3(q[6]);
            const label celli = locator.cell(i);
            const scalar beta = volume*dragK[i];
            const vector dragForce = beta*(U[celli] - up);
            const vector buoyancy = -rho.value()*volume*gravity;
            S[celli] -= dragForce/(rho.value()*mesh.V()[celli]);
            double* f = &reply[proto::kReplyHeader + proto::kForceDoubles*i];
            f[0] = dragForce.x() + buoyancy.x();
            f[1] = dragForce.y() + buoyancy.y();
            f[2] = dragForce.z() + buoyancy.z();
            f[3] = 1;
            f[4] = beta;
            f[5] = U[celli].x();
            f[6] = U[celli].y();
            f[7] = U[celli].z();
        }
        talusFoam::sendForces(inbox, reply, maxRe, halo, exchangeTimer);
        S.correctBoundaryConditions();

        #include "CourantNo.H"
        #include "pisoStep.H"

        runTime.write();
        runTime.printExecutionTime(Info);
        exchangeTimer.stepDone();
    }

    runTime.writeNow();
    link.disconnect();
    Info<< "End\n" << endl;
    if (ownMpi)
    {
        MPI_Finalize();
    }
    return 0;
}


// ************************************************************************* //
