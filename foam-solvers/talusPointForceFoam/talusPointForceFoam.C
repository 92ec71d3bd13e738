/*---------------------------------------------------------------------------*\
Application
    talusPointForceFoam

Description
    Transient incompressible laminar PISO solver (as icoFoam) coupled with the Talus DEM by
    point forces: each fluid step it receives the particles from the DEM process, locates each
    particle's cell on this rank's sub-mesh (walk from the previous cell, octree as fallback),
    returns the Stokes drag 3 pi mu d (u_f - u_p) plus the buoyancy -rho V_p g of each particle,
    and adds the drag's reaction as an explicit momentum source in the particle's cell.

    Started by the DEM side (talus.coupling.FoamCoupling) with MPI_Comm_spawn; serial, or with
    -parallel on a decomposed case. Message protocol: coupling/FoamProtocol.h.

    Case files as icoFoam (0/U, 0/p, system/fvSolution PISO) plus
        constant/transportProperties  nu [m2/s] and rho [kg/m3]
        constant/g                    gravity, compared with the DEM side's

License
    GPL-3.0-or-later, like OpenFOAM.
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"

#include "fvCFD.H"
#include "pisoControl.H"
#include "uniformDimensionedFields.H"

#include <cstdio>

namespace proto = talus::foam_protocol;

static const char* const solverName = "talusPointForceFoam";


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

    const scalar mu = (rho*nu).value();
    const vector gravity = g.value();

    talusFoam::ParticleLocator locator(mesh);
    talusFoam::ExchangeTimer exchangeTimer;
    std::vector<double> particles;    // per particle x y z vx vy vz r index
    std::vector<double> reply;        // header (FoamProtocol.h), then per particle fx fy fz owned beta uf

    Info<< "\nStarting the coupled time loop\n" << endl;

    while (true)
    {
        #include "receiveParticles.H"
        runTime++;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        locator.locate(particles, n, halo);

        reply.assign(proto::kReplyHeader + proto::kForceDoubles*n, 0.0);
        S.primitiveFieldRef() = Zero;
        scalar maxRe = 0;
        for (label i = 0; i < n; ++i)
        {
            if (!locator.owned(i))
            {
                continue;
            }
            const double* q = &particles[proto::kParticleDoubles*i];
            const vector up(q[3], q[4], q[5]);
            const scalar r = q[6];
            const label celli = locator.cell(i);
            const vector slip = U[celli] - up;
            const scalar beta = 3*constant::mathematical::pi*mu*(2*r);
            const vector drag = beta*slip;
            const vector buoyancy =
                -rho.value()*(4.0/3.0)*constant::mathematical::pi*pow3(r)*gravity;
            S[celli] -= drag/(rho.value()*mesh.V()[celli]);
            maxRe = max(maxRe, mag(slip)*2*r/nu.value());
            double* f = &reply[proto::kReplyHeader + proto::kForceDoubles*i];
            f[0] = drag.x() + buoyancy.x();
            f[1] = drag.y() + buoyancy.y();
            f[2] = drag.z() + buoyancy.z();
            f[3] = 1;
            f[4] = beta;
            f[5] = U[celli].x();
            f[6] = U[celli].y();
            f[7] = U[celli].z();
        }
        talusFoam::sendForces(link, reply, maxRe, halo, exchangeTimer);
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
