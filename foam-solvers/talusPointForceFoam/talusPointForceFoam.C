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

#include "demLink.H"

#include "fvCFD.H"
#include "meshSearch.H"
#include "pisoControl.H"
#include "uniformDimensionedFields.H"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace proto = talus::foam_protocol;

namespace
{
bool differs(double a, double b)
{
    return std::abs(a - b) > proto::kMatchTolerance*std::max(std::abs(a), std::abs(b));
}

//- The reason the DEM side's description does not fit this case, or "".
std::string mismatch
(
    const int hello[proto::kHelloInts],
    const double helloD[proto::kHelloDoubles],
    double rho,
    double nu,
    const Foam::vector& g
)
{
    std::ostringstream why;
    if (hello[0] != proto::kMagic)
    {
        why << "the DEM process does not speak the Talus coupling protocol (bad magic number)";
    }
    else if (hello[1] != proto::kVersion)
    {
        why << "protocol version mismatch: DEM side " << hello[1]
            << ", talusPointForceFoam " << proto::kVersion;
    }
    else if (differs(helloD[0], rho))
    {
        why << "fluid density mismatch: DEM side rhoFluid = " << helloD[0]
            << ", case constant/transportProperties rho = " << rho;
    }
    else if (differs(helloD[1], nu))
    {
        why << "kinematic viscosity mismatch: DEM side nu = " << helloD[1]
            << ", case constant/transportProperties nu = " << nu;
    }
    else if
    (
        differs(helloD[2], g.x()) || differs(helloD[3], g.y()) || differs(helloD[4], g.z())
    )
    {
        why << "gravity mismatch: DEM side (" << helloD[2] << " " << helloD[3] << " "
            << helloD[4] << "), case constant/g (" << g.x() << " " << g.y() << " "
            << g.z() << ")";
    }
    return why.str();
}
} // namespace


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

    // The solver's progress goes to the case's log file, not to the DEM process's terminal
    // (Open MPI forwards a spawned process's stdout there); errors still go to stderr.
    if (Pstream::master())
    {
        const fileName log = args.path()/"log.talusPointForceFoam";
        if (!std::freopen(log.c_str(), "w", stdout))
        {
            std::cerr << "talusPointForceFoam: cannot write " << log << ", logging to stdout\n";
        }
    }

    // A serial run has no Pstream MPI: start MPI here to reach the DEM process.
    const bool ownMpi = !Pstream::parRun();
    if (ownMpi)
    {
        int initialised = 0;
        MPI_Initialized(&initialised);
        if (!initialised)
        {
            MPI_Init(&argc, &argv);
        }
    }
    talusFoam::DemLink link(args.getOrDefault<scalar>("couplingTimeout", 60));

    // Handshake, first half: before reading the case, so a solver dying on a bad case file is
    // noticed by the DEM process through its pid at once.
    int hello[proto::kHelloInts];
    double helloD[proto::kHelloDoubles];
    link.recv(hello, proto::kHelloInts, MPI_INT, proto::kTagHello, "the handshake");
    link.recv(helloD, proto::kHelloDoubles, MPI_DOUBLE, proto::kTagHelloD, "the handshake");
    link.watch(hello[3], hello[4]);
    const int self[2] = {static_cast<int>(getpid()), talusFoam::DemLink::thisHost()};
    link.send(self, 2, MPI_INT, proto::kTagPid, "the handshake");

    #include "createTime.H"
    #include "createMesh.H"

    pisoControl piso(mesh);

    #include "createFields.H"
    #include "initContinuityErrs.H"

    const scalar mu = (rho*nu).value();
    const vector gravity = g.value();

    // Handshake, second half: every rank checks the case; rank 0 answers.
    const std::string why = mismatch(hello, helloD, rho.value(), nu.value(), gravity);
    if (Pstream::master())
    {
        const int reply[proto::kReplyInts] =
        {
            proto::kMagic,
            proto::kVersion,
            why.empty() ? proto::kStatusOk : proto::kStatusMismatch,
            Pstream::nProcs(),
            static_cast<int>(returnReduce(mesh.nCells(), sumOp<label>()))
        };
        const double replyD[proto::kReplyDoubles] =
        {
            runTime.deltaTValue(), rho.value(), nu.value()
        };
        link.send(reply, proto::kReplyInts, MPI_INT, proto::kTagHelloReply, "the handshake");
        link.send
        (
            replyD, proto::kReplyDoubles, MPI_DOUBLE, proto::kTagHelloReplyD, "the handshake"
        );
        link.sendMessage(why);
    }
    else
    {
        returnReduce(mesh.nCells(), sumOp<label>());
    }
    if (!why.empty())
    {
        Info<< "talusPointForceFoam: " << why.c_str() << endl;
        link.disconnect();
        if (ownMpi)
        {
            MPI_Finalize();
        }
        return 1;
    }

    meshSearch search(mesh);
    labelList cells;                  // each particle's cell on this rank, -1 if elsewhere
    std::vector<double> particles;    // per particle x y z vx vy vz r
    std::vector<double> reply;        // status, max Re_p, then per particle fx fy fz owned

    Info<< "\nStarting the coupled time loop\n" << endl;

    while (true)
    {
        int command[2];
        link.recv(command, 2, MPI_INT, proto::kTagCommand, "the next command");
        if (command[0] == proto::kCommandStop)
        {
            break;
        }
        const label n = command[1];
        particles.resize(proto::kParticleDoubles*n);
        link.recv
        (
            particles.data(), static_cast<int>(particles.size()), MPI_DOUBLE,
            proto::kTagParticles, "the particles"
        );
        runTime++;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        // Locate: walk from last step's cell (a particle moves a fraction of a cell per step),
        // octree search when the walk stops at a local minimum or the particle is new here.
        cells.setSize(n, -1);
        labelList ownerRank(n, Pstream::nProcs());
        for (label i = 0; i < n; ++i)
        {
            const double* q = &particles[proto::kParticleDoubles*i];
            const point x(q[0], q[1], q[2]);
            label celli = cells[i] >= 0 ? search.findCell(x, cells[i]) : -1;
            if (celli < 0)
            {
                celli = search.findCell(x);
            }
            cells[i] = celli;
            if (celli >= 0)
            {
                ownerRank[i] = Pstream::myProcNo();
            }
        }
        // A particle on a face between two ranks' cells belongs to the lower rank only.
        if (Pstream::parRun())
        {
            MPI_Allreduce
            (
                MPI_IN_PLACE, ownerRank.begin(), n, MPI_INT, MPI_MIN, MPI_COMM_WORLD
            );
        }

        reply.assign(2 + proto::kForceDoubles*n, 0.0);
        S.primitiveFieldRef() = Zero;
        scalar maxRe = 0;
        for (label i = 0; i < n; ++i)
        {
            if (ownerRank[i] != Pstream::myProcNo())
            {
                continue;
            }
            const double* q = &particles[proto::kParticleDoubles*i];
            const vector up(q[3], q[4], q[5]);
            const scalar r = q[6];
            const label celli = cells[i];
            const vector slip = U[celli] - up;
            const vector drag = 3*constant::mathematical::pi*mu*(2*r)*slip;
            const vector buoyancy =
                -rho.value()*(4.0/3.0)*constant::mathematical::pi*pow3(r)*gravity;
            S[celli] -= drag/(rho.value()*mesh.V()[celli]);
            maxRe = max(maxRe, mag(slip)*2*r/nu.value());
            double* f = &reply[2 + proto::kForceDoubles*i];
            f[0] = drag.x() + buoyancy.x();
            f[1] = drag.y() + buoyancy.y();
            f[2] = drag.z() + buoyancy.z();
            f[3] = 1;
        }
        reply[0] = proto::kStatusOk;
        reply[1] = maxRe;
        link.send
        (
            reply.data(), static_cast<int>(reply.size()), MPI_DOUBLE, proto::kTagForces,
            "the forces"
        );
        S.correctBoundaryConditions();

        #include "CourantNo.H"
        #include "pisoStep.H"

        runTime.write();
        runTime.printExecutionTime(Info);
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
