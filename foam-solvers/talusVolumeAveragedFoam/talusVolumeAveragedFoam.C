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
                   / nu (0.44 Re / 24 instead above Re_p 1000); or Stokes, Di Felice, or
                   Ergun / Wen-Yu (dragClosure.H)
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
        envelopeCutoff       c: the envelope is cut at c delta (default 1.274: 3 sigma)
        envelopeMethod       convolution | pairwise (default convolution): the Gaussian by
                             convolution on the lattice of the cell centres
                             (latticeConvolution.H; pairwise where the centres form no equally
                             spaced lattice), or its sums over every particle-cell pair
        dragModel            Stokes | SchillerNaumann | DiFelice | ErgunWenYu
                             (default SchillerNaumann)
        hindranceExponent    h                    (default 2.65; Stokes and SchillerNaumann)
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

#include <algorithm>
#include <array>
#include <cstdio>

namespace proto = talus::foam_protocol;

static const char* const solverName = "talusVolumeAveragedFoam";
// The drag closure without a dragModel entry (the seed chapter's).
static const char* const defaultDragModel = "SchillerNaumann";

namespace
{
// Per cell, what the envelope gathers to the particles (ParticleEnvelope::gather): V, and V
// times alphaf, U, -grad p + nu lap U (the buoyancy's acceleration), DU/Dt. The first sum is
// W_i, the others the interpolations times W_i. The 12th is 0: rows of whole vector registers.
constexpr int kGathered = 12;
// Per particle, what it spreads onto the cells besides its volume: V_p K, V_p K u_p (the
// drag's implicit and explicit parts) and the added mass; the 8th is 0, as above.
constexpr int kReactions = 8;
// Exchanges left out of the phases' timing (see the time loop).
constexpr label kWarmUpExchanges = 2;
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

    talusFoam::ParticleEnvelope envelope
    (
        mesh, envelopeType == "gaussian" ? envelopeWidth : 0, envelopeCutoff*envelopeWidth,
        envelopeMethod == "convolution"
    );
    // A particle concerns every rank with cells within its envelope's reach.
    const scalar couplingMargin = envelope.margin();
    #include "answerDemHandshake.H"

    const scalar rhoF = rho.value();
    const scalar nuF = nu.value();
    const vector gravity = g.value();
    const scalar pi = constant::mathematical::pi;

    talusFoam::ParticleLocator locator(mesh);
    talusFoam::ExchangeTimer exchangeTimer;
    talusFoam::ParticleInbox inbox(link);
    talusFoam::PhaseTimer phases
    (
        {"location", "envelope", "volumes", "fields", "gather", "forces", "reactions"}
    );
    std::vector<double> particles;    // per particle x y z vx vy vz r index
    std::vector<double> reply;        // header (FoamProtocol.h), then per particle fx fy fz owned beta uf
    // The envelope's inputs and outputs, kept between exchanges (no allocation per exchange):
    // per particle its volume, its gathered sums (kGathered, summed over the ranks) and its
    // reactions (kReactions); per cell the solid fraction, what is gathered and the reactions.
    std::vector<double> volumes, gathered, reactions;
    std::vector<double> cellSolid, cellValues(kGathered*mesh.nCells()), cellReactions;
    // Per particle the drag closure's inputs (fluid fraction, slip speed, diameter) and its K.
    std::vector<double> dragAlpha, dragSlip, dragDiameter, dragK;
    // Per particle: its envelope reaches this rank's cells, or this rank owns it (chars, not
    // the bits of a vector<bool>: read once per particle in the forces' loop).
    std::vector<char> touches;
    // By particle index, for du_p/dt: its velocity at the last exchange that had it on this
    // rank, and that exchange's number (-1: none; a vector, not a map: no allocation per
    // particle).
    std::vector<vector> lastVelocity;
    std::vector<label> lastExchange;
    label exchange = 0;
    scalarField alphaNew(mesh.nCells());
    const scalarField& V = mesh.V();
    const scalar inverseRho = 1/rhoF;
    bool first = true;
    double convolutionBefore = 0;

    // What the envelope gathers from the fluid state of this time besides the fluid fraction
    // (kGathered): computed at the start and at the end of each fluid step, from the state the
    // next exchange sees (nothing changes U and p in between), so that the exchange, which the
    // DEM process waits for, does not include it (a gradient and a Laplacian over the mesh, a
    // good part of an exchange); the DEM sub-steps run meanwhile.
    const auto storeFluidValues = [&]()
    {
        const volVectorField gradp(fvc::grad(p));
        const volVectorField lapU(fvc::laplacian(nu, U));
        const volVectorField DUDt(fvc::ddt(U) + (U & fvc::grad(U)));
        forAll(V, c)
        {
            double* v = &cellValues[kGathered*c];
            v[0] = V[c];
            v[11] = 0;
            for (direction k = 0; k < 3; ++k)
            {
                v[2 + k] = V[c]*U[c][k];
                v[5 + k] = V[c]*(lapU[c][k] - gradp[c][k]);
                v[8 + k] = V[c]*DUDt[c][k];
            }
        }
    };
    storeFluidValues();

    Info<< "\nStarting the coupled time loop\n" << endl;

    while (true)
    {
        #include "receiveParticles.H"

        // The phases are timed from the third exchange on: the first builds the octree, the
        // buffers and the per-particle records, many times a later exchange's location.
        if (exchange == kWarmUpExchanges)
        {
            phases.reset();
            convolutionBefore = envelope.convolutionSeconds();
        }
        phases.start();
        locator.locate(particles, n, halo);
        phases.done(0);
        envelope.build(particles, n, locator);
        phases.done(1);

        // Fluid fraction of the particles' new positions.
        volumes.resize(n);
        for (label i = 0; i < n; ++i)
        {
            volumes[i] = 4.0/3.0*pi*pow3(particles[proto::kParticleDoubles*i + 6]);
        }
        envelope.spread<1>(volumes, cellSolid);
        phases.done(2);
        forAll(alphaNew, c)
        {
            alphaNew[c] = max(1 - cellSolid[c], alphaMin);
        }
        if (alphaRelaxationTime > 0 && !first)
        {
            alphaNew =
                alphaf.primitiveField()
              + min(1.0, runTime.deltaTValue()/alphaRelaxationTime)
               *(alphaNew - alphaf.primitiveField());
        }

        // The fluid's own values are in cellValues already (storeFluidValues).
        forAll(alphaNew, c)
        {
            cellValues[kGathered*c + 1] = V[c]*alphaNew[c];
        }
        phases.done(3);
        envelope.gather<kGathered>(cellValues, gathered);
        touches.resize(n);
        for (label i = 0; i < n; ++i)
        {
            touches[i] = gathered[kGathered*i] > 0 || locator.owned(i);
        }
        halo.combine(gathered, kGathered);
        phases.done(4);

        // Forces on the particles (every rank whose cells a particle touches computes it from
        // the same summed values; its owner returns it) and their reactions on the fluid.
        // Every value written below (zeros included) rather than the arrays zeroed first: two
        // fewer passes over memory written anyway.
        reply.resize(proto::kReplyHeader + proto::kForceDoubles*n);
        reactions.resize(kReactions*n);
        const scalar dt = runTime.deltaTValue();
        scalar maxRe = 0;
        // The drag's K of every particle first, in one call (its powers in vector registers,
        // dragClosure.H), from its fluid fraction, slip speed and diameter.
        dragAlpha.resize(n);
        dragSlip.resize(n);
        dragDiameter.resize(n);
        dragK.resize(n);
        for (label i = 0; i < n; ++i)
        {
            const double* q = &particles[proto::kParticleDoubles*i];
            const double* s = &gathered[kGathered*i];
            const scalar inverseW = s[0] > 0 ? 1/s[0] : 0;
            dragAlpha[i] = min(max(s[1]*inverseW, alphaMin), 1.0);
            dragSlip[i] = mag(inverseW*vector(s[2], s[3], s[4]) - vector(q[3], q[4], q[5]));
            dragDiameter[i] = 2*q[6];
        }
        drag.K(n, dragAlpha.data(), dragSlip.data(), dragDiameter.data(), dragK.data());
        for (label i = 0; i < n; ++i)
        {
            double* reaction = &reactions[kReactions*i];
            double* r = &reply[proto::kReplyHeader + proto::kForceDoubles*i];
            if (!touches[i])
            {
                std::fill_n(reaction, kReactions, 0.0);
                std::fill_n(r, proto::kForceDoubles, 0.0);
                continue;
            }
            const double* q = &particles[proto::kParticleDoubles*i];
            const double* s = &gathered[kGathered*i];
            // W_i = 0: no cell of any rank within the cut-off of a particle in its cell (an
            // envelope narrower than the cells): nothing interpolated, as with no pairs.
            const scalar inverseW = s[0] > 0 ? 1/s[0] : 0;
            const vector up(q[3], q[4], q[5]);
            const scalar d = dragDiameter[i];
            const scalar Vp = pi*pow3(d)/6;
            const vector uf = inverseW*vector(s[2], s[3], s[4]);
            const vector slip = uf - up;
            const scalar Re = dragSlip[i]*d/nuF;
            const scalar K = dragK[i];
            const vector dragForce = Vp*K*slip;
            const vector buoyancy =
                Vp*rhoF*inverseW*vector(s[5], s[6], s[7]) - rhoF*Vp*gravity;
            const std::size_t id = static_cast<std::size_t>(q[7]);
            if (id >= lastVelocity.size())
            {
                lastVelocity.resize(id + 1, vector::zero);
                lastExchange.resize(id + 1, -1);
            }
            const bool lastSeen = lastExchange[id] >= 0 && lastExchange[id] == exchange - 1;
            const vector dupdt = lastSeen ? (up - lastVelocity[id])/dt : vector::zero;
            lastVelocity[id] = up;
            lastExchange[id] = exchange;
            const vector addedMass =
                addedMassCoefficient*rhoF*Vp*(inverseW*vector(s[8], s[9], s[10]) - dupdt);
            reaction[0] = Vp*K;
            for (direction k = 0; k < 3; ++k)
            {
                reaction[1 + k] = Vp*K*up[k];
                reaction[4 + k] = addedMass[k];
            }
            reaction[7] = 0;
            if (!locator.owned(i))
            {
                std::fill_n(r, proto::kForceDoubles, 0.0);
            }
            else
            {
                const vector f = dragForce + buoyancy + addedMass;
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
        phases.done(5);
        envelope.spread<kReactions>(reactions, cellReactions);
        forAll(Ksp, c)
        {
            const double* r = &cellReactions[kReactions*c];
            Ksp[c] = r[0]*inverseRho;
            KUp[c] = inverseRho*vector(r[1], r[2], r[3]);
            Sexplicit[c] = -inverseRho*vector(r[4], r[5], r[6]);
        }
        phases.done(6);
        ++exchange;
        talusFoam::sendForces(inbox, reply, maxRe, halo, exchangeTimer);

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

        storeFluidValues();
        runTime.write();
        runTime.printExecutionTime(Info);
        exchangeTimer.stepDone();
    }

    runTime.writeNow();
    // Where the exchanges' time went (cfd_exchange_cost.py reads this line).
    const label timed = max(exchange - kWarmUpExchanges, label(0));
    Info<< "Exchange phases, CPU ms per exchange over " << timed << " after "
        << kWarmUpExchanges << ":" << phases.report(timed).c_str() << " (convolution "
        << (timed > 0 ? 1e3*(envelope.convolutionSeconds() - convolutionBefore)/timed : 0)
        << ")" << endl;
    link.disconnect();
    Info<< "End\n" << endl;
    if (ownMpi)
    {
        MPI_Finalize();
    }
    return 0;
}


// ************************************************************************* //
