/*---------------------------------------------------------------------------*\
Application
    talusVolumeAveragedFoam

Description
    Transient incompressible PIMPLE solver of the volume-averaged Navier-Stokes equations,
    coupled with the Talus DEM (seed chapter "CFD-DEM coupled simulations with Yade and
    OpenFOAM", volume averaged coupling). Each fluid step it receives the particles from the
    DEM process, spreads their volume onto the cells (fluid fraction alphaf) with a Gaussian
    envelope or cell-locally (particleEnvelope.H), interpolates the fluid velocity, pressure
    gradient, viscous stress divergence and material acceleration to the particles, and returns
    per particle
        drag       V_p K (u_f - u_p), by default K = 18 rho nu / d^2 (1 + 0.15 Re_p^0.687)
                   alpha^-h (Schiller-Naumann with the hindrance exponent h), Re_p = |u_f - u_p| d
                   / nu; or Di Felice, or Ergun / Wen-Yu (dragClosure.H)
        buoyancy   V_p rho (-grad p + nu lap U) - rho V_p g   (p without its hydrostatic part)
        added mass C_m rho V_p (Du_f/Dt - du_p/dt), du_p/dt from the last two exchanges.
    The fluid gets the drag's reaction implicitly (-Ksp (U - U_p), hindrance included) and the
    added mass's explicitly, spread with the same envelope.

    Started by the DEM side (talus.coupling.FoamCoupling) with MPI_Comm_spawn; serial, or with
    -parallel on a decomposed case. Message protocol: coupling/FoamProtocol.h.

    Case files: 0/U (interstitial velocity), 0/p (kinematic, without the hydrostatic part),
    system/fvSolution with PIMPLE, constant/transportProperties (nu, rho), constant/g, and
    optionally constant/couplingProperties:
        envelope             gaussian | cell      (default gaussian)
        envelopeWidth        delta [m]            (default 3 x the mean cell size)
        dragModel            SchillerNaumann | DiFelice | ErgunWenYu (default SchillerNaumann)
        hindranceExponent    h                    (default 2.65; SchillerNaumann only)
        addedMassCoefficient C_m                  (default 0.5; 0 switches it off)
        alphaMin             lower bound of alphaf (default 0.2)
        alphaRelaxationTime  T [s]: alphaf relaxes towards the particles' fraction over T
                             (default 0: follows at once)

License
    GPL-3.0-or-later, like OpenFOAM.
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "dragClosure.H"
#include "particleEnvelope.H"

#include "fvCFD.H"
#include "pimpleControl.H"
#include "uniformDimensionedFields.H"

#include <cstdio>
#include <unordered_map>

namespace proto = talus::foam_protocol;

static const char* const solverName = "talusVolumeAveragedFoam";

namespace
{
// Per particle, the envelope's interpolation of: alphaf, U, grad p, nu lap U, DU/Dt.
constexpr int kInterp = 13;
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Volume-averaged PIMPLE solver coupled with the Talus DEM"
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

    pimpleControl pimple(mesh);

    #include "createFields.H"

    // A particle concerns every rank with cells within its envelope's cut-off.
    const scalar couplingMargin =
        envelopeType == "gaussian" ? talusFoam::ParticleEnvelope::cutoffOf(envelopeWidth) : 0;
    #include "answerDemHandshake.H"

    const scalar rhoF = rho.value();
    const scalar nuF = nu.value();
    const vector gravity = g.value();
    const scalar pi = constant::mathematical::pi;

    talusFoam::ParticleLocator locator(mesh);
    talusFoam::ExchangeTimer exchangeTimer;
    talusFoam::ParticleEnvelope envelope(mesh, envelopeType == "gaussian" ? envelopeWidth : 0);
    std::vector<double> particles;    // per particle x y z vx vy vz r index
    std::vector<double> reply;        // header (FoamProtocol.h), then per particle fx fy fz owned beta uf
    std::vector<double> interp;       // kInterp per particle, summed over ranks
    std::unordered_map<label, vector> previousVelocity;  // by particle index, for du_p/dt
    scalarField alphaNew(mesh.nCells());
    const scalarField& V = mesh.V();
    bool first = true;

    Info<< "\nStarting the coupled time loop\n" << endl;

    while (true)
    {
        #include "receiveParticles.H"

        locator.locate(particles, n, halo);
        envelope.build(particles, n, locator, halo);

        // Fluid fraction of the particles' new positions.
        scalarField solid(mesh.nCells(), 0.0);
        for (label i = 0; i < n; ++i)
        {
            const scalar Vp = 4.0/3.0*pi*pow3(particles[proto::kParticleDoubles*i + 6]);
            envelope.forEachSpread(i, [&](label c, double w) { solid[c] += w*Vp/V[c]; });
        }
        alphaNew = max(1 - solid, alphaMin);
        if (alphaRelaxationTime > 0 && !first)
        {
            alphaNew =
                alphaf.primitiveField()
              + min(1.0, runTime.deltaTValue()/alphaRelaxationTime)
               *(alphaNew - alphaf.primitiveField());
        }

        // The fluid quantities the particles feel, from the fluid state of this time.
        const volVectorField gradp(fvc::grad(p));
        const volVectorField lapU(fvc::laplacian(nu, U));
        const volVectorField DUDt(fvc::ddt(U) + (U & fvc::grad(U)));
        interp.assign(kInterp*n, 0.0);
        for (label i = 0; i < n; ++i)
        {
            double* s = &interp[kInterp*i];
            envelope.forEachInterpolation(i, [&](label c, double w)
            {
                s[0] += w*alphaNew[c];
                for (direction k = 0; k < 3; ++k)
                {
                    s[1 + k] += w*U[c][k];
                    s[4 + k] += w*gradp[c][k];
                    s[7 + k] += w*lapU[c][k];
                    s[10 + k] += w*DUDt[c][k];
                }
            });
        }
        halo.combine(interp, kInterp);

        // Forces on the particles (every rank whose cells a particle touches computes it from
        // the same summed values; its owner returns it) and their reactions on the fluid.
        Ksp.primitiveFieldRef() = 0;
        KUp.primitiveFieldRef() = Zero;
        Sexplicit.primitiveFieldRef() = Zero;
        reply.assign(proto::kReplyHeader + proto::kForceDoubles*n, 0.0);
        std::unordered_map<label, vector> velocity;
        const scalar dt = runTime.deltaTValue();
        scalar maxRe = 0;
        for (label i = 0; i < n; ++i)
        {
            if (!envelope.touches(i) && !locator.owned(i))
            {
                continue;
            }
            const double* q = &particles[proto::kParticleDoubles*i];
            const double* s = &interp[kInterp*i];
            const vector up(q[3], q[4], q[5]);
            const scalar d = 2*q[6];
            const scalar Vp = pi*pow3(d)/6;
            const scalar alpha = min(max(s[0], alphaMin), 1.0);
            const vector uf(s[1], s[2], s[3]);
            const vector slip = uf - up;
            const scalar Re = mag(slip)*d/nuF;
            const scalar K = drag.K(alpha, mag(slip), d);
            const vector dragForce = Vp*K*slip;
            const vector buoyancy =
                Vp*rhoF*(vector(-s[4], -s[5], -s[6]) + vector(s[7], s[8], s[9]))
              - rhoF*Vp*gravity;
            const label id = static_cast<label>(q[7]);
            velocity.emplace(id, up);
            const auto last = previousVelocity.find(id);
            const vector dupdt =
                last == previousVelocity.end() ? vector::zero : (up - last->second)/dt;
            const vector addedMass =
                addedMassCoefficient*rhoF*Vp*(vector(s[10], s[11], s[12]) - dupdt);
            envelope.forEachSpread(i, [&](label c, double w)
            {
                const scalar share = w*Vp/(rhoF*V[c]);
                Ksp[c] += share*K;
                KUp[c] += share*K*up;
                Sexplicit[c] -= w*addedMass/(rhoF*V[c]);
            });
            if (locator.owned(i))
            {
                const vector f = dragForce + buoyancy + addedMass;
                double* r = &reply[proto::kReplyHeader + proto::kForceDoubles*i];
                r[0] = f.x();
                r[1] = f.y();
                r[2] = f.z();
                r[3] = 1;
                r[4] = Vp*K;
                r[5] = uf.x();
                r[6] = uf.y();
                r[7] = uf.z();
                maxRe = max(maxRe, Re);
            }
        }
        previousVelocity.swap(velocity);
        talusFoam::sendForces(link, reply, maxRe, halo, exchangeTimer);

        runTime++;
        Info<< "Time = " << runTime.timeName() << nl << endl;

        // The first step starts from the particles' fraction (no d(alphaf)/dt from 1).
        alphaf.primitiveFieldRef() = alphaNew;
        alphaf.correctBoundaryConditions();
        if (first)
        {
            alphaf.oldTime() == alphaf;
            first = false;
        }
        Ksp.correctBoundaryConditions();
        KUp.correctBoundaryConditions();
        Sexplicit.correctBoundaryConditions();
        alphaPhi = fvc::interpolate(alphaf)*phi;

        #include "CourantNo.H"

        while (pimple.loop())
        {
            #include "UEqn.H"
            while (pimple.correct())
            {
                #include "pEqn.H"
            }
        }

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
